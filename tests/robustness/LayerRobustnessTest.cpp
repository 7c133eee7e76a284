// Catalogue section B, cases 18 and 21–23: coincident layers, the distance-lens boundary, clip
// planes through faces and edges, and a camera inside closed meshes.

#include "RobustnessCases.h"
#include "TestRender.h"

#include "tracer/TracerTestUtil.h"
#include "../../framework/src/tracer/TraversalIsa.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <bit>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace mvcl::robustness {
namespace {

void measured(const std::string &line) { std::printf("[ measured ] %s\n", line.c_str()); }

/// Two coincident pairs of cubes: an identical pair (mesh 0 in layer 1 and mesh 1 in layer 0,
/// same vertices and triangles) and a pair whose faces are split along opposite diagonals
/// (meshes 2 and 3, layers 3 and 2), so their t values differ by rounding only.
Scene makeCoincidentScene() {
    Scene scene;
    for (const glm::vec3 colour : {glm::vec3(0.9f, 0.1f, 0.1f), glm::vec3(0.1f, 0.2f, 0.9f),
                                   glm::vec3(0.1f, 0.8f, 0.1f), glm::vec3(0.8f, 0.8f, 0.1f)}) {
        Material m;
        m.diffuse = colour;
        m.ambient = colour;
        scene.materials.push_back(m);
    }
    TriangleMesh a = test::makeBoxMesh({-1.3f, -0.5f, -0.5f}, {-0.3f, 0.5f, 0.5f});
    a.layer = 1;
    a.material = 0;
    TriangleMesh b = a;
    b.layer = 0;
    b.material = 1;
    TriangleMesh c = test::makeBoxMesh({0.3f, -0.5f, -0.5f}, {1.3f, 0.5f, 0.5f});
    c.layer = 3;
    c.material = 2;
    TriangleMesh d = c;
    d.layer = 2;
    d.material = 3;
    for (glm::uvec3 &tri : d.indices) tri = {tri.y, tri.z, tri.x}; // same winding, other start
    for (std::size_t q = 0; q < d.indices.size(); q += 2) {       // flip each quad's diagonal
        const glm::uvec3 t0 = c.indices[q], t1 = c.indices[q + 1]; // (a, b, c), (a, c, d)
        d.indices[q] = {t0.y, t0.z, t1.z};                          // (b, c, d)
        d.indices[q + 1] = {t0.y, t1.z, t0.x};                      // (b, d, a)
    }
    scene.meshes = {a, b, c, d};
    Light light;
    light.position = {2.f, 3.f, 4.f};
    scene.lights.push_back(light);
    return scene;
}

/// Case 18: gap 0. The identical pair resolves to the lower layer everywhere; the images of both
/// pairs are bit-identical across render thread counts, build thread counts, leaf sizes and the
/// SSE/AVX2 traversal.
TEST(RobustnessLayers, CoincidentLayersResolveByTotalOrderWithIdenticalImages) {
    const Scene scene = makeCoincidentScene();
    const Camera camera = Camera::lookAt({0.7f, 1.4f, 3.5f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 50.f);
    std::set<uint64_t> hashes;
    uint64_t renders = 0;
    std::size_t nonFinite = 0;
    for (const int leafSize : {1, 4, 15})
        for (const int buildThreads : {1, 4})
            for (const bool sse : {false, true}) {
                TracerSettings settings;
                settings.maxLeafSize = leafSize;
                settings.buildThreads = buildThreads;
                detail::forceSseTraversal(sse);
                const Tracer tracer(scene, settings);
                detail::forceSseTraversal(false);
                for (const int threads : {1, 2, 5}) {
                    const auto r = test::renderWithPolicy(tracer, camera, 64, 48, 2, threads);
                    hashes.insert(test::framebufferHash(r.image));
                    nonFinite += test::nonFinitePixels(r.image) + r.stats.rays.nonFiniteSamples;
                    ++renders;
                }
            }
    // Which layer wins on the identical pair, ray by ray.
    const Tracer tracer(scene);
    uint64_t rays = 0, wrongWinner = 0, innerShown = 0;
    for (int i = 0; i < 20000; ++i) {
        CaseRng rng(18, uint64_t(i));
        const glm::vec3 target(glm::dvec3(-0.8, 0.0, 0.0) + 0.45 * glm::dvec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
        glm::dvec3 w = rng.unitVector();
        w.x = -std::fabs(w.x); // from the −x side: the other pair is never in the way
        const glm::vec3 eye(glm::dvec3(-0.8, 0.0, 0.0) + 3.0 * w);
        Hit h;
        ++rays;
        if (!tracer.closestHit({eye, target - eye}, {}, h) || h.layer != 0 || h.geometry != 1) ++wrongWinner;
        RayQuery without0;
        without0.layerMask = ~layerBit(0);
        if (tracer.closestHit({eye, target - eye}, without0, h) && h.layer == 1) ++innerShown;
    }
    measured("coincident layers: renders=" + std::to_string(renders) + " distinct framebuffer hashes=" +
             std::to_string(hashes.size()) + "; identical pair rays=" + std::to_string(rays) +
             " wrong winner=" + std::to_string(wrongWinner) + " layer 1 shown when layer 0 is masked=" +
             std::to_string(innerShown));
    EXPECT_EQ(hashes.size(), 1u);
    EXPECT_EQ(nonFinite, 0u);
    EXPECT_EQ(wrongWinner, 0u);
    EXPECT_EQ(innerShown, rays);
}

/// Case 21: a plane at exactly t = d, RayQuery.tMin swept over d ± 8 ulps, 100 repetitions.
/// The [tMin, ∞) rule: a hit is visible iff t ≥ tMin, the same in every repetition, so the set of
/// pixels showing the front plane only shrinks as tMin grows (no flicker); behind it, layer 1
/// (a second plane) shows instead, never nothing.
TEST(RobustnessLayers, DistanceLensBoundaryIsDeterministicAndMonotone) {
    Scene scene;
    TriangleMesh front, back;
    front.positions = {{-50.f, -50.f, 0.f}, {50.f, -50.f, 0.f}, {50.f, 50.f, 0.f}, {-50.f, 50.f, 0.f}};
    front.indices = {{0, 1, 2}, {0, 2, 3}};
    front.layer = 0;
    back = front;
    for (glm::vec3 &p : back.positions) p.z = -1.f;
    back.layer = 1;
    scene.meshes = {front, back};
    const Tracer tracer(scene);
    // Two ray sets: parallel rays (every t is exactly 10, all flip together) and a perspective
    // camera (t varies; the ones within ±8 ulps of d flip one by one).
    struct RaySet {
        std::string name;
        std::vector<Ray> rays;
    };
    std::vector<RaySet> sets(2);
    sets[0].name = "parallel";
    sets[1].name = "perspective";
    const Camera camera = Camera::lookAt({0.f, 0.f, 10.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            sets[0].rays.push_back({{-3.f + 0.19f * float(x), -3.f + 0.17f * float(y), 10.f}, {0.f, 0.f, -1.f}});
            sets[1].rays.push_back(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, 32, 32));
        }
    uint64_t queries = 0, nondeterministic = 0, ruleViolations = 0, nonMonotone = 0, holes = 0, flips = 0;
    for (const RaySet &set : sets) {
        Hit centre;
        ASSERT_TRUE(tracer.closestHit(set.rays[16 * 32 + 16], {}, centre));
        const float d = centre.t;
        std::vector<uint8_t> previous(set.rays.size(), 1);
        for (int k = -8; k <= 8; ++k) {
            float tMin = d;
            for (int s = 0; s < std::abs(k); ++s) tMin = k > 0 ? nextFloatUp(tMin) : nextFloatDown(tMin);
            std::vector<uint8_t> visible(set.rays.size());
            for (std::size_t r = 0; r < set.rays.size(); ++r) {
                Hit unclipped;
                tracer.closestHit(set.rays[r], {}, unclipped);
                RayQuery q;
                q.tMin = tMin;
                Hit first;
                const bool found = tracer.closestHit(set.rays[r], q, first);
                for (int rep = 1; rep < 100; ++rep) {
                    Hit again;
                    const bool f = tracer.closestHit(set.rays[r], q, again);
                    ++queries;
                    if (f != found || std::bit_cast<uint32_t>(again.t) != std::bit_cast<uint32_t>(first.t) ||
                        again.layer != first.layer)
                        ++nondeterministic;
                }
                if (!found) ++holes;
                visible[r] = found && first.layer == 0;
                if (bool(visible[r]) != (unclipped.t >= tMin)) ++ruleViolations;
                if (visible[r] && !previous[r]) ++nonMonotone;
                flips += !visible[r] && previous[r];
                previous[r] = visible[r];
            }
        }
    }
    measured("distance-lens boundary: queries=" + std::to_string(queries) + " nondeterministic=" +
             std::to_string(nondeterministic) + " [d,inf) rule violations=" + std::to_string(ruleViolations) +
             " non-monotone=" + std::to_string(nonMonotone) + " holes=" + std::to_string(holes) +
             " pixels flipping within +-8 ulp=" + std::to_string(flips));
    EXPECT_EQ(nondeterministic, 0u);
    EXPECT_EQ(ruleViolations, 0u);
    EXPECT_EQ(nonMonotone, 0u);
    EXPECT_EQ(holes, 0u);
    EXPECT_GE(flips, 1024u); // the parallel set flips as a whole: the sweep crosses the boundary
}

/// Case 22: clip half-spaces lying exactly in a cube face and through a cube edge. Whether a
/// hit on the plane survives is decided by the rounded hit point o + t·d, so it may go either
/// way; the requirement is that the choice is consistent: BVH = oracle bit for bit, anyHit
/// agrees, and every returned hit satisfies the clip. The watertight re-run inside a clip is
/// RobustnessWatertightClipped.
TEST(RobustnessLayers, ClipPlaneThroughFaceOrEdgeIsConsistent) {
    Scene scene;
    scene.meshes.push_back(test::makeBoxMesh({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}));
    const Tracer tracer(scene);
    const glm::vec3 edgeNormal = glm::normalize(glm::vec3(1.f, 1.f, 0.f));
    struct Clip {
        std::string name;
        ClipVolume volume;
    };
    const std::vector<Clip> clips = {
        {"keep x>=0.5 (in the +x face)", ClipVolume::halfSpace(glm::vec3(1, 0, 0), 0.5f, ClipVolume::Keep::Inside)},
        {"cut x>=0.5 (in the +x face)", ClipVolume::halfSpace(glm::vec3(1, 0, 0), 0.5f, ClipVolume::Keep::Outside)},
        {"keep through the +x+y edge", ClipVolume::halfSpace(edgeNormal, glm::dot(edgeNormal, glm::vec3(0.5f, 0.5f, 0.f)), ClipVolume::Keep::Inside)},
        {"cut through the +x+y edge", ClipVolume::halfSpace(edgeNormal, glm::dot(edgeNormal, glm::vec3(0.5f, 0.5f, 0.f)), ClipVolume::Keep::Outside)},
    };
    uint64_t rays = 0, inconsistent = 0;
    for (const Clip &clip : clips) {
        RayQuery q;
        q.addClip(clip.volume);
        uint64_t onPlaneKept = 0, onPlane = 0;
        for (int i = 0; i < 20000; ++i) {
            CaseRng rng(22, uint64_t(i));
            // Aim at the +x face, half the time at its +y edge.
            const glm::vec3 target(0.5f, i % 2 ? 0.5f : float(rng.uniform(-0.5, 0.5)), float(rng.uniform(-0.5, 0.5)));
            glm::dvec3 w = rng.unitVector();
            if (w.x < 0.0) w.x = -w.x;
            const glm::vec3 eye = target + glm::vec3(3.0 * w);
            const Ray ray{eye, target - eye};
            Hit a, b, plain;
            const bool fa = tracer.closestHit(ray, q, a);
            const bool fb = tracer.closestHitBruteForce(ray, q, b);
            ++rays;
            if (fa != fb || (fa && (std::bit_cast<uint32_t>(a.t) != std::bit_cast<uint32_t>(b.t) ||
                                    a.primitive != b.primitive)) ||
                tracer.anyHit(ray, q) != fa || (fa && !q.acceptsPoint(ray.at(a.t), a.layer)))
                ++inconsistent;
            if (tracer.closestHit(ray, {}, plain) && std::fabs(ray.at(plain.t).x - 0.5f) < 1e-6f) {
                ++onPlane;
                onPlaneKept += fa && a.t == plain.t;
            }
        }
        measured("clip " + clip.name + ": hits in the clip plane kept " + std::to_string(onPlaneKept) + " of " +
                 std::to_string(onPlane));
    }
    measured("clip planes through face/edge: rays=" + std::to_string(rays) + " inconsistent=" + std::to_string(inconsistent));
    EXPECT_EQ(inconsistent, 0u);
}

/// Case 23: the camera inside the outer cube (between the layers) and inside the inner cube of
/// the built-in cube-in-cube scene. Every primary ray hits (the cubes are closed), the hit is
/// the oracle's, and the rendered image has no non-finite sample.
TEST(RobustnessLayers, CameraInsideClosedMeshesRendersFinitelyAndMatchesOracle) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const Tracer tracer(scene);
    uint64_t rays = 0, holes = 0, mismatches = 0, nonFinite = 0;
    // The cubes are centred at (0, 1, 0): outer half size 1, inner 0.45.
    for (const glm::vec3 eye : {glm::vec3(0.3f, 1.6f, 0.7f), glm::vec3(0.1f, 1.05f, 0.2f)}) {
        const Camera camera = Camera::lookAt(eye, {-0.2f, 0.9f, -0.5f}, {0.f, 1.f, 0.f}, 90.f);
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) {
                const Ray ray = camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, 64, 48);
                Hit a, b;
                const bool fa = tracer.closestHit(ray, {}, a);
                const bool fb = tracer.closestHitBruteForce(ray, {}, b);
                ++rays;
                holes += !fa;
                if (fa != fb || (fa && (std::bit_cast<uint32_t>(a.t) != std::bit_cast<uint32_t>(b.t) ||
                                        a.geometry != b.geometry || a.primitive != b.primitive || a.kind != b.kind)))
                    ++mismatches;
            }
        const auto r = test::renderWithPolicy(tracer, camera, 64, 48, 4, 0);
        nonFinite += test::nonFinitePixels(r.image) + r.stats.rays.nonFiniteSamples;
    }
    measured("camera inside meshes: primary rays=" + std::to_string(rays) + " holes=" + std::to_string(holes) +
             " oracle mismatches=" + std::to_string(mismatches) + " non-finite samples=" + std::to_string(nonFinite));
    EXPECT_EQ(holes, 0u);
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(nonFinite, 0u);
}

} // namespace
} // namespace mvcl::robustness
