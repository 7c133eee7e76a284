// Layer priority in closest-hit queries: an outer layer's hit within the error bound of the
// nearest hit (or within the scene's contact tolerance) wins over a nearer inner layer's.

#include <mvcl/tracer/Tracer.h>

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include "TracerTestUtil.h"
#include "../../framework/src/tracer/TraversalIsa.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <random>

namespace mvcl {
namespace {

/// A square of side 2 in the plane z = z0, facing +z, on `layer`, split into `cells`² quads.
TriangleMesh square(float z0, int layer, int cells) {
    TriangleMesh m = test::makeUvSphere(glm::dvec3(0.0), 1.0, 3, 3); // only to get a named mesh
    m.positions.clear();
    m.normals.clear();
    m.indices.clear();
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i)
            m.positions.push_back({-1.f + 2.f * float(i) / float(cells), -1.f + 2.f * float(j) / float(cells), z0});
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const uint32_t a = uint32_t(j * (cells + 1) + i), b = a + 1, c = a + uint32_t(cells) + 1, d = c + 1;
            m.indices.push_back({a, b, d});
            m.indices.push_back({a, d, c});
        }
    m.layer = layer;
    return m;
}

/// Two nested spheres of equal tessellation, the outer (layer 0) scaled by 1 + g.
Scene nestedSpheres(double g) {
    Scene scene;
    scene.materials.resize(1);
    TriangleMesh outer = test::makeUvSphere(glm::dvec3(0.0), 1.0 + g, 24, 48);
    outer.layer = 0;
    TriangleMesh inner = test::makeUvSphere(glm::dvec3(0.0), 1.0, 24, 48);
    inner.layer = 1;
    scene.meshes = {outer, inner};
    return scene;
}

Ray rayAt(std::mt19937 &rng) {
    std::uniform_real_distribution<float> u(-0.9f, 0.9f);
    const glm::vec3 target(u(rng), u(rng), u(rng) * 0.2f);
    const glm::vec3 eye(0.3f, -0.2f, 4.f);
    return {eye, glm::normalize(target - eye)};
}

TEST(LayerPriority, TheWatertightTestReportsAnErrorBoundOfItsT) {
    const glm::vec3 p0(-1.f, -1.f, 2.f), p1(1.f, -1.f, 2.f), p2(0.f, 1.f, 2.f);
    TriangleHit hit{};
    ASSERT_TRUE(intersectTriangle(Ray{{0.1f, 0.f, 0.f}, {0.f, 0.f, 1.f}}, p0, p1, p2, 0.f, 10.f, hit));
    EXPECT_FLOAT_EQ(hit.t, 2.f);
    // Conservative (above the ~ulp the rounding can make) yet a few dozen ulps at most here.
    EXPECT_GT(hit.tError, 0.f);
    EXPECT_LT(hit.tError, 64.f * 2.4e-7f * 2.f);
}

/// At gaps from 0 to a few ulps the inner sphere pokes through by rounding; the outer layer
/// wins on every ray, and the BVH agrees with the brute-force oracle bit for bit.
TEST(LayerPriority, OuterLayerWinsWithinTheErrorBound) {
    for (const double g : {0.0, 1e-7, 3e-7, 1e-6}) {
        const Scene scene = nestedSpheres(g);
        const Tracer tracer(scene);
        std::mt19937 rng(7);
        int inner = 0, mismatches = 0, hits = 0;
        for (int i = 0; i < 20000; ++i) {
            const Ray ray = rayAt(rng);
            Hit a, b;
            const bool fa = tracer.closestHit(ray, {}, a);
            const bool fb = tracer.closestHitBruteForce(ray, {}, b);
            if (fa != fb || (fa && (a.t != b.t || a.layer != b.layer || a.primitive != b.primitive))) ++mismatches;
            if (!fa) continue;
            ++hits;
            if (a.layer != 0) ++inner;
        }
        EXPECT_GT(hits, 15000) << g;
        EXPECT_EQ(inner, 0) << "g = " << g;
        EXPECT_EQ(mismatches, 0) << "g = " << g;
    }
}

/// A masked-out layer is never a candidate: with layer 0 masked the inner sphere shows on every
/// ray that met the pair, and with layer 1 masked nothing changes for the outer one.
TEST(LayerPriority, MaskedOutLayersAreNeverCandidates) {
    const Scene scene = nestedSpheres(1e-7);
    const Tracer tracer(scene);
    std::mt19937 rng(11);
    RayQuery innerOnly;
    innerOnly.layerMask = ~layerBit(0);
    RayQuery outerOnly;
    outerOnly.layerMask = layerBit(0);
    for (int i = 0; i < 5000; ++i) {
        const Ray ray = rayAt(rng);
        Hit all, a, b;
        if (!tracer.closestHit(ray, {}, all)) continue;
        ASSERT_TRUE(tracer.closestHit(ray, innerOnly, a));
        EXPECT_EQ(a.layer, 1);
        ASSERT_TRUE(tracer.closestHit(ray, outerOnly, b));
        EXPECT_EQ(b.layer, 0);
        EXPECT_EQ(b.t, all.t);
        EXPECT_EQ(b.primitive, all.primitive);
    }
}

/// The distance window keeps its meaning: an outer hit beyond tMax is not a candidate, so the
/// inner hit inside the window is returned; anyHit is unchanged by priority.
TEST(LayerPriority, DistanceWindowsAndAnyHitKeepTheirMeaning) {
    Scene scene;
    scene.materials.resize(1);
    // The inner layer (1) in front at z = 0, the outer layer (0) a hair behind.
    const float behind = -1e-6f;
    scene.meshes = {square(0.f, 1, 1), square(behind, 0, 1)};
    const Tracer tracer(scene);
    const Ray ray{{0.1f, 0.2f, 1.f}, {0.f, 0.f, -1.f}};
    Hit hit;
    ASSERT_TRUE(tracer.closestHit(ray, {}, hit));
    EXPECT_EQ(hit.layer, 0); // 1e-6 is within the bound of t = 1 (δt ≈ 4e-7 · … here)
    RayQuery window;
    window.tMax = 1.f; // the inner square's exact t; the outer one lies beyond
    ASSERT_TRUE(tracer.closestHit(ray, window, hit));
    EXPECT_EQ(hit.layer, 1);
    EXPECT_EQ(hit.t, 1.f);
    RayQuery late;
    late.tMin = nextFloatUp(1.f);
    ASSERT_TRUE(tracer.closestHit(ray, late, hit));
    EXPECT_EQ(hit.layer, 0);
    EXPECT_TRUE(tracer.anyHit(ray, window));
}

/// Beyond the error bound the nearer layer wins as before; the contact tolerance widens the
/// window for an outer layer only, in scene units or relative to the scene's size.
TEST(LayerPriority, ContactToleranceLetsAnOuterLayerWinWithinItsDistance) {
    for (const bool innerInFront : {true, false}) {
        Scene scene;
        scene.materials.resize(1);
        const float d = 1e-3f;
        // Layer 1 in front of layer 0 (or the other way round) by d.
        scene.meshes = {square(innerInFront ? 0.f : -d, 1, 4), square(innerInFront ? -d : 0.f, 0, 3)};
        const Ray ray{{0.13f, -0.27f, 2.f}, glm::normalize(glm::vec3(0.05f, 0.02f, -1.f))};
        auto winner = [&](const LayerContact &contact) {
            scene.layerContact = contact;
            const Tracer tracer(scene);
            Hit a, b;
            EXPECT_TRUE(tracer.closestHit(ray, {}, a));
            EXPECT_TRUE(tracer.closestHitBruteForce(ray, {}, b));
            EXPECT_EQ(a.layer, b.layer);
            EXPECT_EQ(a.t, b.t);
            return int(a.layer);
        };
        const int nearer = innerInFront ? 1 : 0;
        EXPECT_EQ(winner({}), nearer);
        EXPECT_EQ(winner({0.5e-3, LayerContact::Measure::SceneUnits}), nearer);
        EXPECT_EQ(winner({2e-3, LayerContact::Measure::SceneUnits}), 0);
        // The scene's diagonal is 2√2 + d: 1e-3 of it is 2.8e-3 > d.
        EXPECT_EQ(winner({1e-3, LayerContact::Measure::RelativeToSceneSize}), 0);
        EXPECT_EQ(winner({1e-4, LayerContact::Measure::RelativeToSceneSize}), nearer);
    }
}

/// Four layers stacked within each other's windows: the answer is a function of the set of
/// hits, the same for every leaf size and for the SSE and AVX2 traversals.
TEST(LayerPriority, ResultDoesNotDependOnTheBvh) {
    Scene scene;
    scene.materials.resize(1);
    for (int layer = 0; layer < 4; ++layer) scene.meshes.push_back(square(-4e-6f * float(3 - layer), layer, 3 + layer));
    std::vector<std::vector<Hit>> results;
    for (const int leaf : {1, 4, 15})
        for (const bool sse : {false, true}) {
            TracerSettings settings;
            settings.maxLeafSize = leaf;
            detail::forceSseTraversal(sse);
            const Tracer tracer(scene, settings);
            std::mt19937 rng(3);
            std::uniform_real_distribution<float> u(-0.9f, 0.9f);
            std::vector<Hit> hits;
            for (int i = 0; i < 4000; ++i) {
                const Ray ray{{u(rng), u(rng), 1.f}, glm::normalize(glm::vec3(u(rng) * 0.3f, u(rng) * 0.3f, -1.f))};
                Hit h;
                tracer.closestHit(ray, {}, h);
                hits.push_back(h);
                Hit o;
                tracer.closestHitBruteForce(ray, {}, o);
                EXPECT_EQ(o.layer, h.layer);
                EXPECT_EQ(o.t, h.t);
            }
            detail::forceSseTraversal(false);
            results.push_back(hits);
        }
    for (std::size_t r = 1; r < results.size(); ++r)
        for (std::size_t i = 0; i < results[0].size(); ++i) {
            EXPECT_EQ(results[r][i].layer, results[0][i].layer);
            EXPECT_EQ(results[r][i].t, results[0][i].t);
            EXPECT_EQ(results[r][i].primitive, results[0][i].primitive);
        }
}

} // namespace
} // namespace mvcl
