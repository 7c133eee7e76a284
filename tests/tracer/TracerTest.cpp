#include <mvcl/tracer/Tracer.h>

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/RayOffset.h>

#include "TracerTestUtil.h"
#include "../../framework/src/tracer/Bvh.h"
#include "../../framework/src/tracer/TraversalIsa.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace mvcl {
namespace {

using test::expectSameHit;
using test::makeSoup;
using test::randomQuery;
using test::randomUnit;

constexpr float kInf = std::numeric_limits<float>::infinity();

Ray randomRay(std::mt19937 &rng, float extent = 1.5f) {
    std::uniform_real_distribution<float> pos(-extent, extent);
    return Ray{{pos(rng), pos(rng), pos(rng)}, randomUnit(rng)};
}

TEST(Tracer, BuildStatsLeaveOutDegenerateGeometry) {
    const Scene scene = makeSoup(4000, 1);
    const Tracer tracer(scene);
    const TracerBuildStats &st = tracer.buildStats();
    EXPECT_EQ(st.triangles, 4000u); // the three junk triangles are left out
    EXPECT_EQ(st.spheres, 9u);
    EXPECT_EQ(st.planes, 1u);
    EXPECT_GT(st.nodes, 1u);
    EXPECT_GT(st.leaves, 0u);
    EXPECT_GT(st.maxDepth, 0);
    EXPECT_GT(st.memoryBytes, 0u);
    EXPECT_GE(st.buildMilliseconds, 0.0);
}

/// Random rays (every other one with a random query) through closestHit, closestHitBruteForce and
/// anyHit: the BVH answer must equal the oracle bitwise and respect the query. Returns the hits.
int compareWithBruteForce(const Tracer &tracer, std::mt19937 &rng, int rays, const std::string &what) {
    int hits = 0;
    for (int i = 0; i < rays; ++i) {
        const Ray ray = randomRay(rng);
        const RayQuery q = i % 2 ? randomQuery(rng) : RayQuery{};
        const std::string label = what + " ray " + std::to_string(i);
        Hit a, b;
        const bool fa = tracer.closestHit(ray, q, a);
        const bool fb = tracer.closestHitBruteForce(ray, q, b);
        expectSameHit(fa, a, fb, b, label);
        EXPECT_EQ(tracer.anyHit(ray, q), fa) << label;
        hits += fa;
        if (fa) {
            EXPECT_TRUE(q.acceptsPoint(ray.at(a.t), a.layer)) << label;
            EXPECT_TRUE((q.layerMask >> a.layer) & 1u) << label;
            EXPECT_GE(a.t, q.tMin) << label;
            EXPECT_LE(a.t, q.tMax) << label;
        }
    }
    return hits;
}

TEST(Tracer, BvhMatchesBruteForceOnSoup) {
    const Scene scene = makeSoup(4000, 2);
    const Tracer tracer(scene);
    std::mt19937 rng(3);
    EXPECT_GT(compareWithBruteForce(tracer, rng, 4000, "soup"), 1000);
}

/// Leaves of one primitive and leaves of up to 15 (four PrimBlocks, partly filled, with spheres
/// among the triangles) give the brute-force answer too.
TEST(Tracer, BvhMatchesBruteForceForAnyLeafSize) {
    const Scene scene = makeSoup(3000, 12);
    for (const int leafSize : {1, 15}) {
        TracerSettings settings;
        settings.maxLeafSize = leafSize;
        const Tracer tracer(scene, settings);
        std::mt19937 rng(13);
        EXPECT_GT(compareWithBruteForce(tracer, rng, 2000, "leaf size " + std::to_string(leafSize)), 500);
    }
}

TEST(Tracer, BvhMatchesBruteForceOnCoplanarAxisAlignedRays) {
    // Rays travelling inside the z = 0.25 plane and rays hitting it head-on exercise the box
    // faces that coincide with triangle planes.
    const Scene scene = makeSoup(2000, 4);
    const Tracer tracer(scene);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> pos(-1.2f, 1.2f);
    for (int i = 0; i < 3000; ++i) {
        Ray ray;
        if (i % 2) ray = Ray{{pos(rng), pos(rng), 1.5f}, {0.f, 0.f, -1.f}};
        else {
            const glm::vec3 d = randomUnit(rng);
            ray = Ray{{pos(rng), pos(rng), 0.25f}, glm::normalize(glm::vec3(d.x, d.y, 0.f))};
        }
        Hit a, b;
        const bool fa = tracer.closestHit(ray, {}, a);
        const bool fb = tracer.closestHitBruteForce(ray, {}, b);
        expectSameHit(fa, a, fb, b, "ray " + std::to_string(i));
    }
}

TEST(Tracer, IdenticalForOneAndTwoBuildThreads) {
    const Scene scene = makeSoup(40000, 6);
    TracerSettings one;
    one.buildThreads = 1;
    const Tracer a(scene, one);
    // Two threads, and more threads than the machine has (other task interleavings).
    for (const int threads : {2, 5}) {
        TracerSettings many;
        many.buildThreads = threads;
        const Tracer b(scene, many);
        EXPECT_EQ(a.buildStats().nodes, b.buildStats().nodes);
        EXPECT_EQ(a.buildStats().leaves, b.buildStats().leaves);
        EXPECT_EQ(a.buildStats().maxDepth, b.buildStats().maxDepth);
        EXPECT_EQ(a.buildStats().memoryBytes, b.buildStats().memoryBytes);
        std::mt19937 rng(7);
        for (int i = 0; i < 3000; ++i) {
            const Ray ray = randomRay(rng);
            const RayQuery q = randomQuery(rng);
            Hit ha, hb;
            const bool fa = a.closestHit(ray, q, ha);
            const bool fb = b.closestHit(ray, q, hb);
            expectSameHit(fa, ha, fb, hb, std::to_string(threads) + " threads, ray " + std::to_string(i));
        }
    }
}

// The AVX2 binning (one vminps per bin with the upper bound negated) must bin exactly as the
// SSE2 one: same bins, same SAH sweep, the same tree bit for bit, for one and two threads.
TEST(Tracer, Avx2AndSseBinningBuildTheSameTree) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> pos(-50.f, 50.f), size(0.001f, 2.f);
    constexpr std::size_t kCount = 150000; // above the size binned as two halves
    auto makeInput = [&](int threads) {
        std::mt19937 r(rng);
        detail::BvhBuildInput input;
        input.prims.allocate(kCount, detail::Pages::HugeWhenLarge);
        input.threads = threads;
        input.maxLeafSize = 15;
        for (std::size_t i = 0; i < kCount; ++i) {
            detail::PrimRecord &p = input.prims[i];
            const glm::vec3 c(pos(r), pos(r), pos(r));
            p.p0 = c;
            p.p1 = c + glm::vec3(size(r), 0.f, size(r) * 0.5f);
            p.p2 = c + glm::vec3(0.f, size(r), -size(r));
            p.geometry = 0;
            p.primitive = uint32_t(i);
            p.kind = uint8_t(detail::PrimKind::Triangle);
            p.layer = uint8_t(i % 3);
            p.pad = 0;
        }
        return input;
    };
    for (const int threads : {1, 2}) {
        detail::forceSseBinning(true);
        const detail::Bvh sse = detail::buildBvh(makeInput(threads));
        detail::forceSseBinning(false);
        const detail::Bvh avx2 = detail::buildBvh(makeInput(threads));
        ASSERT_EQ(sse.nodeCount, avx2.nodeCount) << threads << " threads";
        EXPECT_EQ(sse.leafCount, avx2.leafCount);
        EXPECT_EQ(sse.maxDepth, avx2.maxDepth);
        EXPECT_EQ(sse.order, avx2.order);
        // Slot positions depend on task interleaving with two threads; one thread fixes them.
        if (threads == 1) {
            EXPECT_EQ(0, std::memcmp(sse.nodes.get(), avx2.nodes.get(), sse.nodeCount * sizeof(detail::BvhNode)));
        }
    }
}

// The AVX2 and SSE node tests must visit the same nodes and return bit-identical results.
TEST(Tracer, Avx2AndSseTraversalAgreeBitwise) {
    if (!detail::avx2TraversalAvailable()) GTEST_SKIP() << "no AVX2 traversal on this CPU/build";
    const Scene scene = makeSoup(20000, 9);
    detail::forceSseTraversal(true);
    const Tracer sse(scene);
    detail::forceSseTraversal(false);
    const Tracer avx2(scene);
    std::mt19937 rng(11);
    for (int i = 0; i < 5000; ++i) {
        const Ray ray = randomRay(rng);
        const RayQuery q = randomQuery(rng);
        Hit ha, hb;
        const bool fa = sse.closestHit(ray, q, ha);
        const bool fb = avx2.closestHit(ray, q, hb);
        expectSameHit(fa, ha, fb, hb, "ray " + std::to_string(i));
        EXPECT_EQ(sse.anyHit(ray, q), avx2.anyHit(ray, q)) << "ray " << i;
        Hit bf;
        EXPECT_EQ(fa, sse.closestHitBruteForce(ray, q, bf)) << "ray " << i;
    }
}

TEST(Tracer, LayerMaskSkipsMaskedLayers) {
    Scene scene;
    TriangleMesh outer = test::makeUvSphere({0, 0, 0}, 2.0, 32, 32);
    outer.layer = 0;
    TriangleMesh inner = test::makeUvSphere({0, 0, 0}, 1.0, 32, 32);
    inner.layer = 1;
    scene.meshes = {outer, inner};
    Sphere core;
    core.radius = 0.5f;
    core.layer = 2;
    scene.spheres.push_back(core);
    const Tracer tracer(scene);
    std::mt19937 rng(8);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 d = randomUnit(rng);
        const Ray ray{-5.f * d + 0.1f * randomUnit(rng), d};
        for (int layer = 0; layer < 3; ++layer) {
            RayQuery q;
            q.layerMask = layerBit(layer);
            Hit h;
            ASSERT_TRUE(tracer.closestHit(ray, q, h));
            EXPECT_EQ(h.layer, layer);
            EXPECT_TRUE(tracer.anyHit(ray, q));
            q.layerMask = layersFrom(layer);
            ASSERT_TRUE(tracer.closestHit(ray, q, h));
            EXPECT_EQ(h.layer, layer);
        }
        RayQuery none;
        none.layerMask = layerBit(5);
        Hit h;
        EXPECT_FALSE(tracer.closestHit(ray, none, h));
        EXPECT_FALSE(tracer.anyHit(ray, none));
        none.layerMask = 0;
        EXPECT_FALSE(tracer.closestHit(ray, none, h));
    }
}

TEST(Tracer, DistanceWindowHonoured) {
    Scene scene;
    scene.meshes.push_back(test::makeBoxMesh({-1, -1, -1}, {1, 1, 1}));
    scene.meshes.push_back(test::makeBoxMesh({-3, -3, -3}, {3, 3, 3}));
    const Tracer tracer(scene);
    const Ray ray{{0.1f, 0.2f, 10.f}, {0.f, 0.f, -1.f}};
    Hit h;
    ASSERT_TRUE(tracer.closestHit(ray, {}, h));
    EXPECT_FLOAT_EQ(h.t, 7.f);
    RayQuery q;
    q.tMin = 7.5f; // the layer lens's distance d
    ASSERT_TRUE(tracer.closestHit(ray, q, h));
    EXPECT_FLOAT_EQ(h.t, 9.f);
    q.tMin = 9.5f;
    ASSERT_TRUE(tracer.closestHit(ray, q, h));
    EXPECT_FLOAT_EQ(h.t, 11.f);
    q.tMin = 0.f;
    q.tMax = 6.9f;
    EXPECT_FALSE(tracer.closestHit(ray, q, h));
    EXPECT_FALSE(tracer.anyHit(ray, q));
    q.tMax = 7.f; // inclusive
    EXPECT_TRUE(tracer.closestHit(ray, q, h));
    q.tMin = 9.2f;
    q.tMax = 10.8f;
    EXPECT_FALSE(tracer.closestHit(ray, q, h));
    EXPECT_FALSE(tracer.anyHit(ray, q));
}

/// closestHit() with a range beside the query answers as the query holding that range would,
/// bit for bit: on cube-in-cube (two layers, spheres, a plane) with and without a contact
/// tolerance, and on a soup of one layer, for random rays, queries and ranges.
TEST(Tracer, ClosestHitWithARangeIsTheQueryWithThatRange) {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<float> range(-1.f, 8.f);
    const Scene cubes = makeBuiltinScene("cube-in-cube");
    Scene touching = cubes;
    touching.layerContact = {0.05, LayerContact::Measure::SceneUnits};
    const Scene soup = makeSoup(2000, 5);
    for (const Scene *scene : {&cubes, static_cast<const Scene *>(&touching), &soup}) {
        const Tracer tracer(*scene);
        for (int i = 0; i < 3000; ++i) {
            const Ray ray = randomRay(rng, 4.f);
            const RayQuery q = i % 2 ? randomQuery(rng) : RayQuery{};
            const float tMin = i % 3 ? range(rng) : -kInf, tMax = i % 5 ? range(rng) : kInf;
            RayQuery within = q;
            within.tMin = std::max(q.tMin, tMin);
            within.tMax = std::min(q.tMax, tMax);
            Hit a, b;
            const bool fa = tracer.closestHit(ray, q, tMin, tMax, a);
            const bool fb = tracer.closestHit(ray, within, b);
            expectSameHit(fa, a, fb, b, scene->name + " ray " + std::to_string(i));
        }
    }
}

TEST(Tracer, ClipVolumes) {
    Scene scene;
    scene.meshes.push_back(test::makeBoxMesh({-1, -1, -1}, {1, 1, 1}));
    Sphere s;
    s.radius = 0.5f;
    s.layer = 1;
    scene.spheres.push_back(s);
    const Tracer tracer(scene);
    const Ray ray{{0.f, 0.1f, 10.f}, {0.f, 0.f, -1.f}};
    Hit h;

    RayQuery cut; // box cutaway around the front face: the ray reaches the sphere
    cut.addClip(ClipVolume::box({-2, -2, 0.9f}, {2, 2, 2}, ClipVolume::Keep::Outside));
    ASSERT_TRUE(tracer.closestHit(ray, cut, h));
    EXPECT_EQ(h.kind, GeometryKind::Sphere);
    EXPECT_NEAR(h.t, 10.f - std::sqrt(0.25f - 0.01f), 1e-5f);

    RayQuery keepIn; // keep only inside a sphere of radius 0.3: the sphere's front is outside
    keepIn.addClip(ClipVolume::sphere({0, 0, 0}, 0.3f, ClipVolume::Keep::Inside));
    EXPECT_FALSE(tracer.closestHit(ray, keepIn, h));
    keepIn.clearClips();
    keepIn.addClip(ClipVolume::sphere({0, 0, 0}, 1.5f, ClipVolume::Keep::Inside)); // everything but the far half of the box
    ASSERT_TRUE(tracer.closestHit(ray, keepIn, h));
    EXPECT_FLOAT_EQ(h.t, 9.f);

    RayQuery half; // keep z ≤ 0 only: {p : dot((0,0,-1), p) ≥ 0}, as a keep-inside half-space
    half.addClip(ClipVolume::halfSpace({0, 0, -1}, 0.f, ClipVolume::Keep::Inside));
    ASSERT_TRUE(tracer.closestHit(ray, half, h));
    EXPECT_EQ(h.kind, GeometryKind::Sphere); // far root of the sphere
    EXPECT_NEAR(h.t, 10.f + std::sqrt(0.25f - 0.01f), 1e-5f);
    EXPECT_TRUE(tracer.anyHit(ray, half));
    Hit b;
    ASSERT_TRUE(tracer.closestHitBruteForce(ray, half, b));
    EXPECT_EQ(std::bit_cast<uint32_t>(h.t), std::bit_cast<uint32_t>(b.t));

    RayQuery all = half; // intersection of constraints: also cut z < −0.6 → nothing but the sphere
    all.addClip(ClipVolume::halfSpace({0, 0, -1}, 0.6f, ClipVolume::Keep::Outside));
    ASSERT_TRUE(tracer.closestHit(ray, all, h));
    EXPECT_EQ(h.kind, GeometryKind::Sphere);
}

TEST(Tracer, InvalidRaysMiss) {
    const Scene scene = makeSoup(400, 9);
    const Tracer tracer(scene);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // The valid control ray is aimed at a triangle's centroid, so it hits whatever the soup.
    const TriangleMesh &mesh = scene.meshes.front();
    const glm::uvec3 first = mesh.indices.front();
    const glm::vec3 centroid = (mesh.positions[first.x] + mesh.positions[first.y] + mesh.positions[first.z]) / 3.f;
    const Ray good{{0.f, 0.f, 5.f}, centroid - glm::vec3(0.f, 0.f, 5.f)};
    Hit h;
    ASSERT_TRUE(tracer.closestHit(good, {}, h));
    std::vector<Ray> bad = {
        {{nan, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {{0.f, 0.f, 5.f}, {0.f, nan, -1.f}},
        {{kInf, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {{0.f, 0.f, 5.f}, {0.f, 0.f, -kInf}},
        {{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}},   {{0.f, 0.f, 5.f}, {-0.f, 0.f, -0.f}},
    };
    for (const Ray &r : bad) {
        Hit untouched;
        untouched.t = 42.f;
        EXPECT_FALSE(tracer.closestHit(r, {}, untouched));
        EXPECT_EQ(untouched.t, 42.f);
        EXPECT_FALSE(tracer.anyHit(r, {}));
        EXPECT_FALSE(tracer.closestHitBruteForce(r, {}, untouched));
    }
    RayQuery q;
    q.tMin = 2.f;
    q.tMax = 1.f;
    EXPECT_FALSE(tracer.closestHit(good, q, h));
    EXPECT_FALSE(tracer.anyHit(good, q));
    q.tMin = nan;
    q.tMax = kInf;
    EXPECT_FALSE(tracer.closestHit(good, q, h));
    q.tMin = 0.f;
    q.tMax = nan;
    EXPECT_FALSE(tracer.closestHit(good, q, h));
}

TEST(Tracer, AxisParallelRaysWithSignedZerosOnSlabPlanes) {
    Scene scene;
    scene.meshes.push_back(test::makeBoxMesh({0, 0, 0}, {1, 1, 1}));
    scene.meshes.push_back(test::makeBoxMesh({2, 0, 0}, {3, 1, 1}));
    const Tracer tracer(scene);
    for (float zero : {0.f, -0.f}) {
        // Origins exactly on the x = 0 and x = 1 slab planes, travelling along z.
        for (float x : {0.f, 1.f, 0.5f}) {
            for (float y : {0.f, 0.5f, 1.f}) {
                const Ray ray{{x, y, -1.f}, {zero, zero, 1.f}};
                Hit h, b;
                const bool f = tracer.closestHit(ray, {}, h);
                const bool fb = tracer.closestHitBruteForce(ray, {}, b);
                ASSERT_TRUE(f) << x << " " << y << " zero sign " << std::signbit(zero);
                EXPECT_EQ(h.t, 1.f);
                expectSameHit(f, h, fb, b, "axis ray");
                EXPECT_TRUE(tracer.anyHit(ray, {}));
            }
        }
        // Along x inside the face plane y = 0 (origin on two slab planes at once).
        const Ray along{{-1.f, 0.f, 0.f}, {1.f, zero, zero}};
        Hit h, b;
        const bool f = tracer.closestHit(along, {}, h);
        const bool fb = tracer.closestHitBruteForce(along, {}, b);
        ASSERT_TRUE(f);
        EXPECT_EQ(h.t, 1.f);
        expectSameHit(f, h, fb, b, "along");
        // Missing to the side: parallel to a slab, outside it.
        const Ray miss{{1.5f, 0.5f, -1.f}, {zero, zero, 1.f}};
        EXPECT_FALSE(tracer.closestHit(miss, {}, h));
        EXPECT_FALSE(tracer.anyHit(miss, {}));
    }
}

TEST(Tracer, WatertightThroughTheBvh) {
    // The BVH must not leak where the triangle test does not: rays from inside a far-away
    // tessellated sphere aimed at its vertices all hit.
    for (const glm::dvec3 center : {glm::dvec3(0.0), glm::dvec3(148376.0, 1234.0, -223423.0)}) {
        Scene scene;
        scene.meshes.push_back(test::makeUvSphere(center, 2.0, 200, 200));
        const Tracer tracer(scene);
        const TriangleMesh &mesh = scene.meshes[0];
        std::mt19937 rng(10);
        std::uniform_int_distribution<std::size_t> pick(0, mesh.positions.size() - 1);
        std::uniform_real_distribution<double> inside(-0.5, 0.5);
        int leaks = 0;
        for (int i = 0; i < 20000; ++i) {
            const glm::vec3 o(center + glm::dvec3{inside(rng), inside(rng), inside(rng)});
            const Ray ray{o, mesh.positions[pick(rng)] - o};
            if (!tracer.anyHit(ray, {})) ++leaks;
            Hit h;
            if (!tracer.closestHit(ray, {}, h)) ++leaks;
        }
        EXPECT_EQ(leaks, 0);
    }
}

TEST(Tracer, InteractionGeometry) {
    Scene scene;
    TriangleMesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.normals = {{0, 0, -1}, {0, 0, -1}, {0, 0, -1}}; // flipped: must come back on Ng's side
    tri.indices = {{0, 1, 2}};
    tri.material = 0;
    tri.layer = 3;
    scene.meshes.push_back(tri);
    Sphere s;
    s.center = {5, 0, 0};
    s.radius = 1;
    s.material = 0;
    s.layer = 1;
    scene.spheres.push_back(s);
    Plane p;
    p.normal = {0, 1, 0};
    p.offset = -2;
    p.layer = 2;
    scene.planes.push_back(p);
    scene.materials.resize(1);
    const Tracer tracer(scene);

    Hit h;
    Ray r{{0.25f, 0.25f, 1.f}, {0, 0, -1}};
    ASSERT_TRUE(tracer.closestHit(r, {}, h));
    SurfaceInteraction si = tracer.interaction(r, h);
    EXPECT_NEAR(si.position.x, 0.25f, 1e-6f);
    EXPECT_NEAR(si.position.y, 0.25f, 1e-6f);
    EXPECT_EQ(si.geometricNormal, glm::vec3(0, 0, 1));
    EXPECT_EQ(si.shadingNormal, glm::vec3(0, 0, 1));
    EXPECT_EQ(si.layer, 3);

    r = Ray{{5.f, 0.f, 5.f}, {0, 0, -1}};
    ASSERT_TRUE(tracer.closestHit(r, {}, h));
    EXPECT_EQ(h.kind, GeometryKind::Sphere);
    si = tracer.interaction(r, h);
    EXPECT_NEAR(glm::length(si.position - s.center), 1.f, 1e-6f);
    EXPECT_NEAR(si.geometricNormal.z, 1.f, 1e-6f);
    EXPECT_EQ(si.layer, 1);

    r = Ray{{7.f, 5.f, 3.f}, glm::normalize(glm::vec3(0.3f, -1.f, 0.2f))};
    ASSERT_TRUE(tracer.closestHit(r, {}, h));
    EXPECT_EQ(h.kind, GeometryKind::Plane);
    si = tracer.interaction(r, h);
    EXPECT_NEAR(si.position.y, -2.f, 1e-6f);
    EXPECT_EQ(si.geometricNormal, glm::vec3(0, 1, 0));
    EXPECT_EQ(si.layer, 2);
}

/// pbrt-v4 Triangle.Reintersect: rays spawned from a hit point with offsetRayOrigin never hit
/// the surface they leave, at every scale from 1e-6 to 1e6.
TEST(Tracer, SpawnedRaysDoNotReintersect) {
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> uni(0.f, 1.f), expo(-6.f, 6.f);
    int spawned = 0, reHits = 0;
    for (int s = 0; s < 500; ++s) {
        const float scale = std::pow(10.f, expo(rng));
        const glm::vec3 shift = scale * glm::vec3{uni(rng), uni(rng), uni(rng)} * 4.f;
        Scene scene;
        if (s % 5 == 4) {
            Sphere sp;
            sp.center = shift;
            sp.radius = scale * (0.1f + uni(rng));
            scene.spheres.push_back(sp);
        } else {
            TriangleMesh mesh;
            for (int k = 0; k < 3; ++k)
                mesh.positions.push_back(shift + scale * glm::vec3{uni(rng), uni(rng), uni(rng)});
            mesh.indices = {{0, 1, 2}};
            scene.meshes.push_back(mesh);
        }
        const Tracer tracer(scene);
        const glm::vec3 target =
            s % 5 == 4 ? scene.spheres[0].center
                       : (scene.meshes[0].positions[0] + scene.meshes[0].positions[1] +
                          scene.meshes[0].positions[2]) / 3.f;
        for (int i = 0; i < 20; ++i) {
            const glm::vec3 o = target + 4.f * scale * randomUnit(rng);
            const Ray ray{o, target - o};
            Hit h;
            if (!tracer.closestHit(ray, {}, h)) continue;
            const SurfaceInteraction si = tracer.interaction(ray, h);
            for (int j = 0; j < 10; ++j) {
                glm::vec3 w = randomUnit(rng);
                // Leave on the side we came from (reflection-like) or the other (refraction-like).
                const glm::vec3 po = offsetRayOrigin(si.position, si.positionError,
                                                     si.geometricNormal, w);
                const Ray spawn{po, w};
                Hit again;
                ++spawned;
                if (s % 5 == 4) {
                    // A ray into a sphere hits its far side; only a hit right at the origin is
                    // a re-intersection.
                    if (tracer.closestHit(spawn, {}, again) &&
                        again.t < 1e-3f * scene.spheres[0].radius)
                        ++reHits;
                } else if (tracer.closestHit(spawn, {}, again)) {
                    ++reHits;
                }
            }
        }
    }
    EXPECT_GT(spawned, 10000);
    EXPECT_EQ(reHits, 0);
}

// Rays outside Tracer::bounds() are left out of whole frames untraced: every hit must lie in it.
TEST(Tracer, BoundsHoldEveryHitAndLeavePlanesOut) {
    const Scene cube = makeBuiltinScene("cube-in-cube");
    // No degenerate triangles: the scene's own bounds, rounded outward by the BVH's boxes.
    const Bounds3f cubeBox = Tracer(cube).bounds(), sceneBox = cube.bounds();
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(cubeBox.min[axis], sceneBox.min[axis]);
        EXPECT_GE(cubeBox.max[axis], sceneBox.max[axis]);
        EXPECT_NEAR(cubeBox.min[axis], sceneBox.min[axis], 1e-5f);
        EXPECT_NEAR(cubeBox.max[axis], sceneBox.max[axis], 1e-5f);
    }

    const Scene scene = makeSoup(2000, 5);
    const Tracer tracer(scene);
    const Bounds3f box = tracer.bounds();
    ASSERT_FALSE(box.isEmpty());
    std::mt19937 rng(11);
    int inside = 0;
    for (int i = 0; i < 4000; ++i) {
        const Ray ray = randomRay(rng, 3.f);
        Hit hit;
        if (!tracer.closestHit(ray, RayQuery{}, hit) || hit.kind == GeometryKind::Plane) continue;
        const glm::vec3 p = ray.at(hit.t);
        const glm::vec3 slack = 1e-5f * (glm::abs(p) + 1.f);
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, box.min - slack)) && glm::all(glm::lessThanEqual(p, box.max + slack)))
            << "ray " << i;
        ++inside;
    }
    EXPECT_GT(inside, 200);

    Scene planesOnly;
    planesOnly.materials.resize(1);
    planesOnly.planes.push_back({"floor", {0.f, 1.f, 0.f}, 0.f, 0, 0});
    EXPECT_TRUE(Tracer(planesOnly).bounds().isEmpty());
}

} // namespace
} // namespace mvcl
