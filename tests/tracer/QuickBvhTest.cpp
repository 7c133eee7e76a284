// The quick BVH (BvhQuality::Quick, a Morton-order build) answers every query as the full SAH
// build does, bit for bit: on random soups against brute force, on real models, under layer
// masks, distance windows and clip volumes, in packets, for any thread count, and on inputs that
// defeat a Morton grid (every centroid in one cell, coordinates whose extent overflows).

#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include "TracerTestUtil.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>

using namespace mvcl;

namespace {

using test::expectSameHit;
using test::makeSoup;
using test::randomQuery;
using test::randomUnit;

const std::filesystem::path kModels = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";

TracerSettings quick(int threads = 0, int maxLeafSize = 4) {
    TracerSettings s;
    s.bvhQuality = BvhQuality::Quick;
    s.buildThreads = threads;
    s.maxLeafSize = maxLeafSize;
    return s;
}

/// Random rays from inside and around the scene under random queries: closest and any hits of
/// `a` against `b`, and of `a` against its own brute force every `bruteEvery` rays. Returns hits.
int compareTracers(const Tracer &a, const Tracer &b, int rays, uint32_t seed, int bruteEvery = 4) {
    const Bounds3f bounds = a.scene().bounds();
    const glm::vec3 lo = bounds.min - 0.5f * (bounds.max - bounds.min);
    const glm::vec3 hi = bounds.max + 0.5f * (bounds.max - bounds.min);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    int hits = 0;
    for (int i = 0; i < rays; ++i) {
        const Ray ray{glm::mix(lo, hi, glm::vec3(unit(rng), unit(rng), unit(rng))), randomUnit(rng)};
        const RayQuery q = randomQuery(rng);
        Hit ha, hb;
        const bool fa = a.closestHit(ray, q, ha);
        expectSameHit(fa, ha, b.closestHit(ray, q, hb), hb, "ray " + std::to_string(i));
        EXPECT_EQ(a.anyHit(ray, q), b.anyHit(ray, q)) << "ray " << i;
        if (i % bruteEvery == 0) {
            Hit bf;
            const bool fbf = a.closestHitBruteForce(ray, q, bf);
            expectSameHit(fa, ha, fbf, bf, "brute force, ray " + std::to_string(i));
        }
        hits += fa;
    }
    return hits;
}

} // namespace

TEST(QuickBvh, AnswersAsTheFullBuildAndBruteForceForAnyLeafSize) {
    const Scene scene = makeSoup(6000, 3);
    const Tracer full(scene);
    for (const int leafSize : {1, 4, 15}) {
        SCOPED_TRACE("leaf size " + std::to_string(leafSize));
        const Tracer fast(scene, quick(0, leafSize));
        EXPECT_EQ(fast.buildStats().bvhQuality, BvhQuality::Quick);
        EXPECT_EQ(fast.buildStats().triangles, full.buildStats().triangles);
        EXPECT_EQ(fast.buildStats().spheres, full.buildStats().spheres);
        EXPECT_GT(compareTracers(fast, full, 3000, 5), 500);
    }
    EXPECT_EQ(full.buildStats().bvhQuality, BvhQuality::Full);
}

TEST(QuickBvh, SameTreeForAnyThreadCount) {
    const Scene scene = makeSoup(60000, 4); // large enough for subtree tasks
    const Tracer one(scene, quick(1));
    for (const int threads : {2, 5}) {
        const Tracer many(scene, quick(threads));
        EXPECT_EQ(one.buildStats().nodes, many.buildStats().nodes);
        EXPECT_EQ(one.buildStats().leaves, many.buildStats().leaves);
        EXPECT_EQ(one.buildStats().maxDepth, many.buildStats().maxDepth);
        EXPECT_EQ(one.buildStats().memoryBytes, many.buildStats().memoryBytes);
        compareTracers(one, many, 2000, 6, 1000);
    }
}

TEST(QuickBvh, AnswersAsTheFullBuildOnModels) {
    const Scene engine = loadScene((kModels / "2CylinderEngine" / "2CylinderEngine.glb").string());
    const Scene kidney = loadScene((kModels / "HRA_Kidney_Female_Left" / "VH_F_Kidney_L.glb").string());
    const Scene cubes = makeBuiltinScene("cube-in-cube");
    for (const Scene *scene : {&engine, &kidney, &cubes}) {
        SCOPED_TRACE(scene->name);
        const Tracer fast(*scene, quick());
        const Tracer full(*scene);
        test::expectSameClosestHits(fast, full, 2000);
        compareTracers(fast, full, 2000, 7, 50);
    }
}

TEST(QuickBvh, PacketsAnswerAsSingleRays) {
    const Scene scene = loadScene((kModels / "2CylinderEngine" / "2CylinderEngine.glb").string());
    const Tracer fast(scene, quick());
    const Bounds3f b = scene.bounds();
    const glm::vec3 eye = b.max + (b.max - b.min);
    const glm::vec3 centre = 0.5f * (b.min + b.max);
    int hits = 0;
    for (int tile = 0; tile < 64; ++tile) {
        std::array<Ray, Tracer::kPacketSize> rays;
        for (int i = 0; i < Tracer::kPacketSize; ++i) {
            const glm::vec3 target = centre + (b.max - b.min) * glm::vec3((tile % 8 + (i % 4) / 4.f) / 8.f - 0.5f,
                                                                         (tile / 8 + (i / 4) / 4.f) / 8.f - 0.5f, 0.f);
            rays[std::size_t(i)] = Ray{eye, glm::normalize(target - eye)};
        }
        const RayQuery q;
        std::array<Hit, Tracer::kPacketSize> packet;
        const uint32_t mask = fast.closestHits(rays, q, packet);
        const uint32_t occluded = fast.anyHits(rays, q);
        for (int i = 0; i < Tracer::kPacketSize; ++i) {
            Hit single;
            const bool found = fast.closestHit(rays[std::size_t(i)], q, single);
            expectSameHit(found, single, (mask >> i) & 1u, packet[std::size_t(i)], "tile " + std::to_string(tile));
            EXPECT_EQ(fast.anyHit(rays[std::size_t(i)], q), bool((occluded >> i) & 1u));
            hits += found;
        }
    }
    EXPECT_GT(hits, 64);
}

TEST(QuickBvh, CentroidsInOneGridCellAreSplitAtTheMedian) {
    // Thousands of triangles around one point: one Morton code for all, a balanced tree anyway.
    Scene scene;
    scene.materials.resize(1);
    TriangleMesh mesh;
    std::mt19937 rng(2);
    for (uint32_t i = 0; i < 20000; ++i) {
        const uint32_t base = uint32_t(mesh.positions.size());
        for (int k = 0; k < 3; ++k) mesh.positions.push_back(1e-6f * randomUnit(rng));
        mesh.indices.push_back({base, base + 1, base + 2});
    }
    // One far triangle gives the grid an extent that puts all the others into one cell.
    const uint32_t base = uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {{100.f, 0.f, 0.f}, {101.f, 0.f, 0.f}, {100.f, 1.f, 0.f}});
    mesh.indices.push_back({base, base + 1, base + 2});
    scene.meshes.push_back(mesh);
    const Tracer fast(scene, quick());
    EXPECT_LE(fast.buildStats().maxDepth, 40);
    const Tracer full(scene);
    std::mt19937 rays(3);
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 d = randomUnit(rays);
        const Ray ray{-d, d};
        Hit a, b;
        const bool fa = fast.closestHit(ray, {}, a);
        expectSameHit(fa, a, full.closestHit(ray, {}, b), b, "ray " + std::to_string(i));
    }
}

TEST(QuickBvh, OverflowingExtentsBuildAndAnswer) {
    // Coordinates near ±3.4e38: the extent is infinite, the grid's scale falls back to 0.
    Scene scene;
    scene.materials.resize(1);
    TriangleMesh mesh;
    mesh.positions = {{-3e38f, 0.f, 0.f}, {-3e38f, 1.f, 0.f}, {-3e38f, 0.f, 1.f},
                      {3e38f, 0.f, 0.f},  {3e38f, 1.f, 0.f},  {3e38f, 0.f, 1.f},
                      {0.f, -1.f, -1.f},  {0.f, 1.f, -1.f},   {0.f, 0.f, 1.f}};
    mesh.indices = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
    scene.meshes.push_back(mesh);
    const Tracer fast(scene, quick());
    EXPECT_EQ(fast.buildStats().triangles, 3u);
    Hit hit;
    ASSERT_TRUE(fast.closestHit(Ray{{-1.f, 0.f, 0.f}, {1.f, 0.f, 0.f}}, {}, hit));
    EXPECT_FLOAT_EQ(hit.t, 1.f);
    EXPECT_EQ(hit.primitive, 2u);
}
