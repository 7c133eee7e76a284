#include <mvcl/tracer/WhittedIntegrator.h>

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

using namespace mvcl;

namespace {

bool finite(const glm::vec3 &c) { return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z); }

Scene singleSphereScene(const Material &material) {
    Scene s;
    s.materials.push_back(material);
    s.spheres.push_back({"ball", {0.f, 0.f, 0.f}, 1.f, 0, 0});
    s.background = glm::vec3(0.25f, 0.5f, 0.75f);
    s.ambientLight = glm::vec3(0.f);
    return s;
}

} // namespace

TEST(WhittedIntegrator, MissReturnsBackground) {
    Scene s = singleSphereScene(Material{});
    const Tracer tracer(s);
    RayCounters counters;
    const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 5.f, 5.f}, {0.f, 0.f, 1.f}}, {}, counters);
    EXPECT_EQ(c, s.background);
    EXPECT_EQ(counters.primary, 1u);
}

TEST(WhittedIntegrator, LambertTermFollowsEquationOne) {
    Material m;
    m.diffuse = glm::vec3(0.5f);
    m.ambient = glm::vec3(0.f);
    Scene s = singleSphereScene(m);
    Light light;
    light.type = LightType::Directional;
    light.direction = {0.f, 0.f, -1.f}; // shines along −z onto the +z pole
    light.intensity = glm::vec3(2.f);
    s.lights.push_back(light);
    const Tracer tracer(s);
    RayCounters counters;
    const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
    EXPECT_NEAR(c.r, 1.f, 1e-5f); // I · P · (L·N) = 2 · 0.5 · 1
    EXPECT_EQ(counters.shadow, 1u);
}

TEST(WhittedIntegrator, GlassSphereTransmitsAndNeverProducesNaN) {
    Material glass;
    glass.diffuse = glm::vec3(0.f);
    glass.ambient = glm::vec3(0.f);
    glass.transparency = 1.f;
    glass.ior = 1.5f;
    Scene s = singleSphereScene(glass);
    const Tracer tracer(s);
    const WhittedIntegrator integrator(tracer);
    // Rays from the centre line to grazing: total internal reflection happens inside for the
    // grazing ones; every result stays finite and bounded by the background.
    for (int i = 0; i <= 100; ++i) {
        const float y = 0.999f * float(i) / 100.f;
        RayCounters counters;
        const glm::vec3 c = integrator.radiance({{0.f, y, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
        EXPECT_TRUE(finite(c)) << "y=" << y;
        EXPECT_LE(c.b, s.background.b * 1.0001f);
        EXPECT_GT(counters.refraction, 0u);
    }
    // Straight through the centre almost everything is transmitted (Fresnel ≈ 4% per face).
    RayCounters counters;
    const glm::vec3 centre = integrator.radiance({{0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
    EXPECT_GT(centre.b, 0.8f * s.background.b);
}

TEST(WhittedIntegrator, FacingMirrorsTerminateAtTheDepthLimit) {
    Scene s;
    Material mirror;
    mirror.reflectivity = 1.f;
    mirror.diffuse = glm::vec3(0.f);
    mirror.ambient = glm::vec3(0.f);
    s.materials.push_back(mirror);
    s.planes.push_back({"a", {0.f, 0.f, 1.f}, -1.f, 0, 0});
    s.planes.push_back({"b", {0.f, 0.f, -1.f}, -1.f, 0, 0});
    const Tracer tracer(s);
    RayPolicy policy;
    policy.shading.maxDepth = 1000000; // clamped internally
    RayCounters counters;
    const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 0.f, 0.f}, {0.f, 0.01f, 1.f}}, policy, counters);
    EXPECT_TRUE(finite(c));
    EXPECT_LE(counters.reflection, 64u);
    EXPECT_GE(counters.reflection, 10u);
}

TEST(WhittedIntegrator, ShadowPolicyControlsOcclusion) {
    // A small sphere between a directional light and a large one.
    Scene s;
    Material m;
    m.ambient = glm::vec3(0.f);
    m.diffuse = glm::vec3(1.f);
    s.materials.push_back(m);
    s.spheres.push_back({"big", {0.f, 0.f, 0.f}, 1.f, 0, 0});
    s.spheres.push_back({"blocker", {0.f, 3.f, 0.f}, 0.5f, 0, 1});
    Light light;
    light.type = LightType::Directional;
    light.direction = {0.f, -1.f, 0.f};
    s.lights.push_back(light);
    const Tracer tracer(s);
    const WhittedIntegrator integrator(tracer);
    const Ray down{{0.f, 1.5f, 0.f}, {0.f, -1.f, 0.f}}; // starts below the blocker
    RayCounters counters;
    RayPolicy policy;
    EXPECT_NEAR(integrator.radiance(down, policy, counters).r, 0.f, 1e-6f);
    policy.shading.shadowStrength = 0.5f;
    EXPECT_NEAR(integrator.radiance(down, policy, counters).r, 0.5f, 1e-5f);
    policy.shading.shadowStrength = 1.f;
    policy.query(RayType::Shadow).layerMask = layerBit(0); // the blocker (layer 1) casts no shadow
    EXPECT_NEAR(integrator.radiance(down, policy, counters).r, 1.f, 1e-5f);
    policy = RayPolicy{};
    policy.shading.shadows = false;
    EXPECT_NEAR(integrator.radiance(down, policy, counters).r, 1.f, 1e-5f);
}

TEST(WhittedIntegrator, ColourPolicyIsAppliedAfterShading) {
    Scene s = singleSphereScene(Material{});
    const Tracer tracer(s);
    RayPolicy policy;
    const glm::vec3 luma(0.2126f, 0.7152f, 0.0722f);
    // Every row is the luminance weights, so each output channel is dot(luma, c).
    policy.color.matrix = glm::transpose(glm::mat3(luma, luma, luma));
    RayCounters counters;
    const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 5.f, 5.f}, {0.f, 0.f, 1.f}}, policy, counters);
    const float y = glm::dot(luma, s.background);
    EXPECT_NEAR(c.r, y, 1e-6f);
    EXPECT_NEAR(c.g, y, 1e-6f);
    EXPECT_NEAR(c.b, y, 1e-6f);
}

TEST(WhittedIntegrator, TransparentOccludersPassTheirTransparencyIntoShadows) {
    // A glass shell of transparency 0.5 between the light and a lit sphere: light passes through
    // both of the shell's surfaces, so 0.5 · 0.5 of it arrives.
    Scene s;
    Material lit;
    lit.ambient = glm::vec3(0.f);
    lit.diffuse = glm::vec3(1.f);
    Material glass = lit;
    glass.transparency = 0.5f;
    s.materials = {lit, glass};
    s.spheres.push_back({"lit", {0.f, 0.f, 0.f}, 1.f, 0, 0});
    s.spheres.push_back({"shell", {0.f, 3.f, 0.f}, 0.5f, 1, 0});
    Light light;
    light.type = LightType::Directional;
    light.direction = {0.f, -1.f, 0.f};
    s.lights.push_back(light);
    const Tracer tracer(s);
    RayCounters counters;
    const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 1.5f, 0.f}, {0.f, -1.f, 0.f}}, {}, counters);
    EXPECT_NEAR(c.r, 0.25f, 1e-5f);
    EXPECT_EQ(counters.shadow, 1u);
}

// radianceFromHit() is what the renderer calls with a packet's primary hits: given the primary
// ray's closest hit (or its miss), it must return radiance()'s value bit for bit and count the
// same rays, over the default scene (two layers, glass, mirrors, spheres, a plane) and the onion.
TEST(WhittedIntegrator, RadianceFromAKnownPrimaryHitIsRadiance) {
    for (const char *name : {"cube-in-cube", "onion"}) {
        SCOPED_TRACE(name);
        const Scene scene = makeBuiltinScene(name);
        const Tracer tracer(scene);
        const WhittedIntegrator integrator(tracer);
        RayPolicy policy;
        policy.color.matrix = glm::mat3(0.9f); // a colour map too
        const IntegratorPlan plan = integrator.plan(policy, StageSelection::SkipUnneeded);
        const Bounds3f b = scene.bounds();
        const glm::vec3 eye = b.center() + 1.5f * glm::length(b.extent()) * glm::normalize(glm::vec3(0.4f, 0.5f, 1.f));
        int hits = 0;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 32; ++x) {
                const glm::vec3 target = b.min + glm::vec3((float(x) + 0.5f) / 32.f, (float(y) + 0.5f) / 24.f, 0.5f) * b.extent();
                const Ray ray{eye, glm::normalize(target - eye)};
                RayCounters expectedCounters, counters;
                const glm::vec3 expected = integrator.radiance(ray, policy, plan, expectedCounters);
                Hit hit;
                const bool found = tracer.closestHit(ray, policy.query(RayType::Primary), hit);
                hits += found;
                const glm::vec3 value = integrator.radianceFromHit(ray, found ? &hit : nullptr, policy, plan, counters);
                for (int k = 0; k < 3; ++k)
                    ASSERT_EQ(std::bit_cast<uint32_t>(value[k]), std::bit_cast<uint32_t>(expected[k])) << x << "," << y;
                ASSERT_EQ(counters.total(), expectedCounters.total()) << x << "," << y;
                ASSERT_EQ(counters.primary, 1u);
            }
        EXPECT_GT(hits, 100);
    }
}

// radianceFromHits() is what the renderer calls for a 4×4 block of primary rays: a stream whose
// shadow rays go as packets per light and whose reflected and refracted rays form waves traced in
// packets. Each value must be radiance()'s bit for bit with the same rays counted: on models whose
// tree takes packets (Duck, 2CylinderEngine with their default key and fill point lights, the
// mosquito in amber: refraction, transparent shadows) and on the default scene (one node: ray by
// ray; a mirror, glass and a reflective floor), under a plain policy, tinted half-strength
// shadows, a layer mask, a capped clip (points on a cap keep their own shadow query), translucent
// layers with edge lines, and shallow trace depth.
TEST(WhittedIntegrator, RadianceFromHitsOfABlockIsRadianceRayByRay) {
    const std::filesystem::path models = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";
    for (const std::string &source :
         {(models / "Duck" / "Duck.glb").string(), (models / "2CylinderEngine" / "2CylinderEngine.glb").string(),
          (models / "MosquitoInAmber" / "MosquitoInAmber.glb").string(), std::string("builtin:cube-in-cube")}) {
        SCOPED_TRACE(source);
        const Scene scene = loadScene(source);
        ASSERT_FALSE(scene.lights.empty());
        const Tracer tracer(scene);
        const WhittedIntegrator integrator(tracer);
        const Bounds3f b = scene.bounds();
        std::vector<RayPolicy> policies(4);
        policies[1].shading.shadowStrength = 0.5f;
        policies[1].shading.shadowTint = {0.2f, 0.3f, 1.f};
        policies[2].query(RayType::Primary).layerMask = 0b10;
        ClipVolume cut = ClipVolume::halfSpace({0.f, 0.f, 1.f}, b.center().z, ClipVolume::Keep::Outside);
        cut.setCapStyle(ClipVolume::CapStyle::Solid);
        policies[3].query(RayType::Primary).addClip(cut);
        policies.emplace_back().shading.layerOpacity[0] = 0.4f;
        policies.back().shading.edges.mode = EdgeLineMode::Triangles;
        policies.emplace_back().shading.maxDepth = 1;
        const glm::vec3 eye = b.center() + 1.2f * glm::length(b.extent()) * glm::normalize(glm::vec3(0.4f, 0.5f, 1.f));
        for (std::size_t k = 0; k < policies.size(); ++k) {
            SCOPED_TRACE(k);
            const RayPolicy &policy = policies[k];
            const IntegratorPlan plan = integrator.plan(policy, StageSelection::SkipUnneeded);
            uint64_t shadowRays = 0;
            for (int by = 0; by < 40; by += 4)
                for (int bx = 0; bx < 40; bx += 4) {
                    std::array<Ray, Tracer::kPacketSize> rays;
                    std::array<Hit, Tracer::kPacketSize> hits;
                    for (int i = 0; i < Tracer::kPacketSize; ++i) {
                        const float x = (float(bx + i % 4) + 0.5f) / 40.f, y = (float(by + i / 4) + 0.5f) / 40.f;
                        const glm::vec3 target = b.min + glm::vec3(x, y, 0.5f) * b.extent();
                        rays[size_t(i)] = Ray{eye, glm::normalize(target - eye)};
                    }
                    const uint32_t found = tracer.closestHits(rays, policy.query(RayType::Primary), hits);
                    std::array<glm::vec3, Tracer::kPacketSize> values;
                    std::array<RayCounters, Tracer::kPacketSize> perRay;
                    integrator.radianceFromHits(rays, hits, found, policy, plan, perRay, values);
                    RayCounters counters, expectedCounters;
                    for (int i = 0; i < Tracer::kPacketSize; ++i) {
                        RayCounters own;
                        const glm::vec3 expected = integrator.radiance(rays[size_t(i)], policy, plan, own);
                        for (int c = 0; c < 3; ++c)
                            ASSERT_EQ(std::bit_cast<uint32_t>(values[size_t(i)][c]), std::bit_cast<uint32_t>(expected[c]))
                                << bx << "," << by << " ray " << i;
                        // Each ray's own cost, as adaptive sampling weighs its pixel's error by it.
                        ASSERT_EQ(perRay[size_t(i)].total(), own.total()) << bx << "," << by << " ray " << i;
                        counters += perRay[size_t(i)];
                        expectedCounters += own;
                    }
                    ASSERT_EQ(counters.total(), expectedCounters.total());
                    ASSERT_EQ(counters.shadow, expectedCounters.shadow);
                    ASSERT_EQ(counters.reflection, expectedCounters.reflection);
                    ASSERT_EQ(counters.refraction, expectedCounters.refraction);
                    // A translucent hit's ray goes on through the surface as a primary ray.
                    ASSERT_EQ(counters.primary, expectedCounters.primary);
                    ASSERT_GE(counters.primary, uint64_t(Tracer::kPacketSize));
                    shadowRays += counters.shadow;
                }
            // The layer mask hides the whole of a one-layer model (Duck): nothing to light there.
            if (k != 2 || scene.meshes.size() > 1) {
                EXPECT_GT(shadowRays, 100u);
            }
        }
    }
}

TEST(WhittedIntegrator, RadianceFromHitsRejectsOversizedBlocks) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    std::vector<Ray> rays(Tracer::kPacketSize + 1);
    std::vector<Hit> hits(rays.size());
    std::vector<glm::vec3> values(rays.size());
    std::vector<RayCounters> counters(rays.size());
    EXPECT_THROW(integrator.radianceFromHits(rays, hits, 0, {}, {}, counters, values), Error);
    EXPECT_THROW(integrator.radianceFromHits(std::span<const Ray>(rays.data(), 4), std::span<const Hit>(hits.data(), 3), 0,
                                             {}, {}, counters, values),
                 Error);
    EXPECT_THROW(integrator.radianceFromHits(std::span<const Ray>(rays.data(), 4), std::span<const Hit>(hits.data(), 4), 0,
                                             {}, {}, std::span<RayCounters>(counters.data(), 3), values),
                 Error);
}

// A sample known to miss (outside the camera footprint of the tracer's bounds) takes the miss
// answer without a ray: it must be what a traced miss gives, with the same counts, and there must
// be none where a miss draws something of its own.
TEST(WhittedIntegrator, PlainMissRadianceIsATracedMiss) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    std::vector<RayPolicy> policies(3);
    policies[1].color.matrix = glm::mat3(0.5f);
    policies[1].color.offset = {0.1f, 0.f, 0.2f};
    policies[2].shading.edges.mode = EdgeLineMode::Triangles;
    const Ray away{{0.f, 1.f, 10.f}, {0.f, 0.f, 1.f}}; // leaves the scene, above the floor
    for (const RayPolicy &policy : policies) {
        const IntegratorPlan plan = integrator.plan(policy, StageSelection::SkipUnneeded);
        RayCounters traced, plain;
        const glm::vec3 expected = integrator.radiance(away, policy, plan, traced);
        glm::vec3 value;
        ASSERT_TRUE(integrator.plainMissRadiance(policy, plan, value, plain));
        EXPECT_EQ(value, expected);
        plain.primary += 1; // the primary ray the answer stands for
        EXPECT_EQ(plain.total(), traced.total());
        EXPECT_EQ(plain.skippedColorMaps, traced.skippedColorMaps);
        EXPECT_EQ(plain.nonFiniteSamples, traced.nonFiniteSamples);
    }
    RayPolicy outlines;
    outlines.shading.edges.mode = EdgeLineMode::Outlines;
    RayPolicy capped;
    ClipVolume cut = ClipVolume::halfSpace({0.f, 0.f, 1.f}, 0.f, ClipVolume::Keep::Outside);
    cut.setCapStyle(ClipVolume::CapStyle::Solid);
    capped.query(RayType::Primary).addClip(cut);
    for (const RayPolicy &policy : {outlines, capped}) {
        glm::vec3 value;
        RayCounters counters;
        EXPECT_FALSE(integrator.plainMissRadiance(policy, integrator.plan(policy, StageSelection::SkipUnneeded), value,
                                                  counters));
    }
}
