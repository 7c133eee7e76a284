// Catalogue section C: total internal reflection (24), the recursion limit with facing mirrors
// (25), the NaN hunt with floating-point traps (26) and the bias floor (28).

#include "RobustnessCases.h"
#include "TestRender.h"

#include "tracer/TracerTestUtil.h"

#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cfenv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace mvcl {
namespace {

void measured(const std::string &line) { std::printf("[ measured ] %s\n", line.c_str()); }

bool isFiniteColour(const glm::vec3 &c) { return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z); }

/// Case 24. Glass (n = 1.5) fills y < 0 (a Plane, so the surface is exactly flat); a ray inside
/// it meets the surface at angle θ. Above, an opaque plane shows green (ambient only); below, one
/// shows red. The radiance is R·red + T·green with Schlick's R, so: finite for every θ, and for
/// θ beyond the critical angle 41.81° exactly red (Fresnel = 1), with no refracted ray traced.
TEST(RobustnessShading, TotalInternalReflectionIsExactAndFinite) {
    Scene scene;
    Material glass;
    glass.ambient = glass.diffuse = glm::vec3(0.f);
    glass.transparency = 1.f;
    glass.ior = 1.5f;
    Material green, red;
    green.ambient = {0.f, 1.f, 0.f};
    green.diffuse = glm::vec3(0.f);
    red.ambient = {1.f, 0.f, 0.f};
    red.diffuse = glm::vec3(0.f);
    scene.materials = {glass, green, red};
    scene.planes.push_back({"glass surface", {0.f, 1.f, 0.f}, 0.f, 0, 0});
    scene.planes.push_back({"sky", {0.f, -1.f, 0.f}, -10.f, 1, 0});   // y = 10
    scene.planes.push_back({"floor", {0.f, 1.f, 0.f}, -10.f, 2, 0});  // y = −10
    scene.ambientLight = glm::vec3(1.f);
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    const double critical = std::asin(1.0 / 1.5) * 180.0 / 3.14159265358979;
    std::vector<double> angles;
    for (int i = 0; i <= 890; ++i) angles.push_back(0.1 * i);
    for (int i = -20; i <= 20; ++i) angles.push_back(critical + 1e-5 * i); // across the critical angle
    uint64_t nonFinite = 0, wrongTir = 0, refractedBeyond = 0, tirCount = 0;
    double worstBelow = 0;
    for (const double degrees : angles) {
        const double theta = degrees * 3.14159265358979 / 180.0;
        const Ray ray{{0.f, -1.f, 0.f}, glm::vec3(glm::dvec3(std::sin(theta), std::cos(theta), 0.0))};
        RayPolicy policy;
        policy.shading.maxDepth = 1;
        RayCounters counters;
        const glm::vec3 c = integrator.radiance(ray, policy, counters);
        if (!isFiniteColour(c) || counters.nonFiniteSamples) ++nonFinite;
        const float cosI = float(ray.direction.y);
        const float k = 1.f - 1.5f * 1.5f * (1.f - cosI * cosI); // the integrator's own TIR test
        if (k < 0.f) {
            ++tirCount;
            if (c != glm::vec3(1.f, 0.f, 0.f)) ++wrongTir;
            refractedBeyond += counters.refraction > 0;
        } else {
            // Schlick with the transmitted-side cosine, as the integrator uses when exiting.
            const double cosT = std::sqrt(double(k));
            const double r0 = 0.04, m = 1.0 - cosT;
            const double fresnel = r0 + (1 - r0) * m * m * m * m * m;
            worstBelow = std::max({worstBelow, std::fabs(c.r - fresnel), std::fabs(c.g - (1 - fresnel))});
        }
    }
    measured("total internal reflection: angles=" + std::to_string(angles.size()) + " beyond critical=" +
             std::to_string(tirCount) + " non-finite=" + std::to_string(nonFinite) + " Fresnel!=1 beyond critical=" +
             std::to_string(wrongTir) + " refracted beyond critical=" + std::to_string(refractedBeyond) +
             " worst |R,T - Schlick| below critical=" + std::to_string(worstBelow));
    EXPECT_EQ(nonFinite, 0u);
    EXPECT_GT(tirCount, 400u);
    EXPECT_EQ(wrongTir, 0u);
    EXPECT_EQ(refractedBeyond, 0u);
    // Float rounding of cosT = √k is amplified near the critical angle (k → 0): ~4e-4 there.
    EXPECT_LT(worstBelow, 1e-3);
}

/// Case 25. Two facing mirrors (reflectivity ρ, ambient a), a ray bouncing between them: the
/// radiance is a·Σ_{k=0}^{D} ρ^k with D = min(maxDepth, 64) (the integrator's ceiling), the number
/// of reflection rays is D, and the time grows at most linearly; maxDepth up to 1e4 terminates.
TEST(RobustnessShading, FacingMirrorsMatchTheTruncatedGeometricSeries) {
    for (const float rho : {0.9f, 1.f}) {
        Scene scene;
        Material mirror;
        mirror.ambient = glm::vec3(0.25f);
        mirror.diffuse = glm::vec3(0.f);
        mirror.reflectivity = rho;
        scene.materials.push_back(mirror);
        scene.planes.push_back({"a", {0.f, 0.f, 1.f}, -1.f, 0, 0});
        scene.planes.push_back({"b", {0.f, 0.f, -1.f}, -1.f, 0, 0});
        scene.ambientLight = glm::vec3(1.f);
        const Tracer tracer(scene);
        const WhittedIntegrator integrator(tracer);
        for (const int maxDepth : {0, 1, 2, 10, 63, 64, 65, 1000, 10000}) {
            RayPolicy policy;
            policy.shading.maxDepth = maxDepth;
            RayCounters counters;
            const auto start = std::chrono::steady_clock::now();
            const glm::vec3 c = integrator.radiance({{0.f, 0.f, 0.f}, glm::normalize(glm::vec3(0.f, 0.01f, 1.f))}, policy, counters);
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            const int depth = std::min(maxDepth, 64);
            double series = 0.0;
            for (int k = 0; k <= depth; ++k) series += std::pow(double(rho), k);
            series *= 0.25;
            EXPECT_NEAR(c.r, series, 1e-5 * series) << "rho " << rho << " maxDepth " << maxDepth;
            EXPECT_EQ(counters.reflection, uint64_t(depth)) << "rho " << rho << " maxDepth " << maxDepth;
            EXPECT_LT(ms, 50.0) << "maxDepth " << maxDepth;
            if (maxDepth == 10000)
                measured("facing mirrors rho=" + std::to_string(rho) + " maxDepth=1e4: reflections=" +
                         std::to_string(counters.reflection) + " radiance=" + std::to_string(c.r) + " series=" +
                         std::to_string(series) + " time=" + std::to_string(ms) + " ms");
        }
    }
}

/// The NaN-hunt scenes: zero and cancelling interpolated normals, shading normals facing away,
/// a point light exactly on a vertex and on a sphere, shininess 0 with nDotH = 0 (pow(0, 0)),
/// a light with zero attenuation, a zero-direction directional light, ior 1 glass.
Scene makeNanHuntScene() {
    Scene scene;
    Material plain;
    plain.specular = 1.f;
    plain.shininess = 0.f; // pow(0, 0)
    Material glass;
    glass.transparency = 1.f;
    glass.ior = 1.f;
    glass.reflectivity = 0.5f;
    Material shiny;
    shiny.specular = 1.f;
    shiny.shininess = 1.f;
    shiny.reflectivity = 1.f;
    scene.materials = {plain, glass, shiny};
    TriangleMesh zeroNormals = test::makeBoxMesh({-2.f, -0.5f, -0.5f}, {-1.f, 0.5f, 0.5f});
    zeroNormals.normals.assign(zeroNormals.positions.size(), glm::vec3(0.f));
    TriangleMesh cancelling = test::makeBoxMesh({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f});
    for (std::size_t i = 0; i < cancelling.positions.size(); ++i)
        cancelling.normals.push_back(i % 2 ? glm::vec3(0.f, 0.f, 1.f) : glm::vec3(0.f, 0.f, -1.f));
    cancelling.material = 2;
    TriangleMesh backFacing = test::makeUvSphere({2.0, 0.0, 0.0}, 0.6, 16, 16);
    for (glm::vec3 &n : backFacing.normals) n = -n;
    backFacing.material = 1;
    scene.meshes = {zeroNormals, cancelling, backFacing};
    scene.spheres.push_back({"lit from its surface", {0.f, 1.5f, 0.f}, 0.5f, 0, 0});
    scene.planes.push_back({"floor", glm::normalize(glm::vec3(0.01f, 1.f, 0.02f)), -0.6f, 2, 0});
    Light onVertex;
    onVertex.position = zeroNormals.positions[7];
    Light onSphere;
    onSphere.position = {0.f, 2.f, 0.f}; // on the sphere's top
    Light noFalloff;
    noFalloff.position = {1.f, 3.f, 2.f};
    noFalloff.constantAttenuation = 0.f; // D = 0
    Light zeroDirection;
    zeroDirection.type = LightType::Directional;
    zeroDirection.direction = glm::vec3(0.f);
    scene.lights = {onVertex, onSphere, noFalloff, zeroDirection};
    return scene;
}

/// Renders the NaN-hunt scene single-threaded (so the calling thread's FP environment applies).
test::TestRender renderNanHunt() {
    const Scene scene = makeNanHuntScene();
    const Tracer tracer(scene);
    const Camera camera = Camera::lookAt({0.37f, 2.1f, 4.3f}, {0.05f, 0.1f, -0.03f}, {0.f, 1.f, 0.f}, 70.f);
    return test::renderWithPolicy(tracer, camera, 48, 36, 2, 1);
}

/// Case 26. 0 non-finite pixels and 0 non-finite samples: the integrator counts every sample it
/// had to replace by black (RayCounters::nonFiniteSamples), so a NaN born anywhere in shading
/// fails this test even though the image itself is sanitised.
///
/// The catalogue also asks for a run with FE_INVALID|FE_DIVBYZERO trapping. It is done in a
/// forked child and reported, not asserted: the tracer's 4-wide triangle kernel computes 1/det
/// and t on all four lanes and masks the results, so inactive lanes divide by zero and multiply
/// 0·∞ by design (as Ize's slab test does for ±0 directions). The child therefore traps inside
/// the tracer, before shading could be checked; see docs/robustness.md.
TEST(RobustnessShading, NanHuntFindsNoNonFiniteSample) {
    const auto r = renderNanHunt();
    measured("NaN hunt: pixels=" + std::to_string(r.image.pixels().size()) + " samples=" +
             std::to_string(r.stats.samples) + " non-finite pixels=" + std::to_string(test::nonFinitePixels(r.image)) +
             " non-finite samples=" + std::to_string(r.stats.rays.nonFiniteSamples) + " shadow rays=" +
             std::to_string(r.stats.rays.shadow));
    EXPECT_EQ(test::nonFinitePixels(r.image), 0u);
    EXPECT_EQ(r.stats.rays.nonFiniteSamples, 0u);
    EXPECT_GT(r.stats.rays.shadow, 0u);
#if defined(__linux__) && defined(__GLIBC__)
    std::fflush(nullptr);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        feenableexcept(FE_INVALID | FE_DIVBYZERO);
        const auto trapped = renderNanHunt();
        _exit(trapped.stats.rays.nonFiniteSamples == 0 ? 0 : 3); // kFoundNonFinite
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    // A trap ends the child by SIGFPE, or (under AddressSanitizer, which handles SIGFPE) by
    // exit code 1. Traps are expected: the BVH builder's SAH divides by empty areas and the
    // SIMD kernel by zero on masked lanes, both discarding the result.
    constexpr int kFoundNonFinite = 3;
    const bool trapped = (WIFSIGNALED(status) && WTERMSIG(status) == SIGFPE) ||
                         (WIFEXITED(status) && WEXITSTATUS(status) == 1);
    const bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    measured(std::string("NaN hunt with FE_INVALID|FE_DIVBYZERO traps (informational): ") +
             (trapped ? "trapped (expected: masked SIMD lanes, empty SAH bins)" : clean ? "clean" : "failed"));
    // A child that ran to the end must have found no non-finite sample either.
    EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == kFoundNonFinite);
#endif
}

/// Case 28 (a measurement with a bound): RMSE against a 1024-spp reference falls with the
/// sample count at a log-log slope of at most −0.5 (jittered sampling gives about −0.75 on
/// edges); a floor (slope flattening towards 0) would mean a bias such as acne or leaks.
TEST(RobustnessShading, ErrorFallsWithSampleCountWithoutABiasFloor) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    const auto reference = test::renderWithPolicy(tracer, camera, 32, 24, 1024, 0);
    std::vector<double> logSpp, logRmse;
    std::string table = "bias floor: spp, RMSE vs 1024 spp\n";
    for (const int spp : {1, 4, 16, 64}) {
        const auto r = test::renderWithPolicy(tracer, camera, 32, 24, spp, 0);
        double sum = 0;
        for (std::size_t i = 0; i < r.image.pixels().size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const double d = double(r.image.pixels()[i][c]) - double(reference.image.pixels()[i][c]);
                sum += d * d;
            }
        const double rmse = std::sqrt(sum / double(3 * r.image.pixels().size()));
        logSpp.push_back(std::log(double(spp)));
        logRmse.push_back(std::log(rmse));
        char row[64];
        std::snprintf(row, sizeof row, "  %3d %.3e\n", spp, rmse);
        table += row;
    }
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < logSpp.size(); ++i) {
        mx += logSpp[i] / double(logSpp.size());
        my += logRmse[i] / double(logSpp.size());
    }
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < logSpp.size(); ++i) {
        sxy += (logSpp[i] - mx) * (logRmse[i] - my);
        sxx += (logSpp[i] - mx) * (logSpp[i] - mx);
    }
    const double slope = sxy / sxx;
    const double lastSlope = (logRmse[3] - logRmse[2]) / (logSpp[3] - logSpp[2]);
    std::printf("%s", table.c_str());
    measured("bias floor: log-log slope " + std::to_string(slope) + " (last segment " + std::to_string(lastSlope) + ")");
    EXPECT_LE(slope, -0.5);
    EXPECT_LE(lastSlope, -0.5);
}

} // namespace
} // namespace mvcl
