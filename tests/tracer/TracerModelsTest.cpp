// BVH against brute force on real glTF models (the loader's output, so real topology, shared
// vertices, slivers and duplicates).

#include <mvcl/model/GltfLoader.h>
#include <mvcl/tracer/RayOffset.h>
#include <mvcl/tracer/Tracer.h>

#include "../../framework/src/tracer/TraversalIsa.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <bit>
#include <filesystem>
#include <memory>
#include <random>
#include <string>

namespace mvcl {
namespace {

class TracerModels : public ::testing::TestWithParam<std::string> {};

Scene loadModel(const std::string &name) {
    return loadGltf(std::filesystem::path(MVCL_TEST_DATA_DIR) / "models" / name / (name + ".glb"));
}

/// A tracer on the default traversal (AVX2 where available) or forced onto the SSE baseline.
std::unique_ptr<Tracer> buildTracer(const Scene &scene, bool forceSse) {
    detail::forceSseTraversal(forceSse);
    auto tracer = std::make_unique<Tracer>(scene);
    detail::forceSseTraversal(false);
    return tracer;
}

TEST_P(TracerModels, BvhMatchesBruteForce) {
    const Scene scene = loadModel(GetParam());
    // Both traversal variants (AVX2 where available, and the SSE baseline) against the oracle.
    for (const bool forceSse : {false, true}) {
        SCOPED_TRACE(forceSse ? "SSE traversal" : "default traversal");
        const auto owned = buildTracer(scene, forceSse);
        const Tracer &tracer = *owned;
        ASSERT_GT(tracer.buildStats().triangles, 0u);
        const Bounds3f b = scene.bounds();
        const glm::vec3 c = b.center();
        const float r = 0.5f * glm::length(b.extent());
        std::mt19937 rng(21);
        std::uniform_real_distribution<float> uni(0.f, 1.f);
        std::normal_distribution<float> n(0.f, 1.f);
        int hits = 0;
        const int kRays = 600;
        for (int i = 0; i < kRays; ++i) {
            const glm::vec3 target = b.min + glm::vec3{uni(rng), uni(rng), uni(rng)} * b.extent();
            glm::vec3 o;
            if (i % 3 == 2) o = b.min + glm::vec3{uni(rng), uni(rng), uni(rng)} * b.extent();
            else o = c + 2.f * r * glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
            const Ray ray{o, glm::normalize(target - o)};
            RayQuery q;
            if (i % 4 == 3) q.tMin = r * uni(rng);
            Hit h, bf;
            const bool fh = tracer.closestHit(ray, q, h);
            const bool fb = tracer.closestHitBruteForce(ray, q, bf);
            ASSERT_EQ(fh, fb) << "ray " << i;
            EXPECT_EQ(tracer.anyHit(ray, q), fh) << "ray " << i;
            if (!fh) continue;
            ++hits;
            EXPECT_EQ(std::bit_cast<uint32_t>(h.t), std::bit_cast<uint32_t>(bf.t)) << "ray " << i;
            EXPECT_EQ(h.geometry, bf.geometry) << "ray " << i;
            EXPECT_EQ(h.primitive, bf.primitive) << "ray " << i;
            EXPECT_EQ(h.kind, bf.kind) << "ray " << i;
        }
        EXPECT_GT(hits, kRays / 10);
    }
}

/// Shadow segments leaving surfaces towards a light, as a renderer casts them: any-hit starts
/// deep in the tree next to the surface, with a full stack (the paths that test a pending node
/// alongside the current one). anyHit must agree with closestHit on every segment, in both
/// traversal variants.
TEST_P(TracerModels, ShadowSegmentsAgreeWithClosestHit) {
    const Scene scene = loadModel(GetParam());
    for (const bool forceSse : {false, true}) {
        SCOPED_TRACE(forceSse ? "SSE traversal" : "default traversal");
        const auto owned = buildTracer(scene, forceSse);
        const Tracer &tracer = *owned;
        const Bounds3f b = scene.bounds();
        const glm::vec3 c = b.center();
        const float r = 0.5f * glm::length(b.extent());
        const glm::vec3 lights[2] = {c + 2.f * r * glm::vec3(0.4f, 1.2f, 0.6f),
                                     c + 0.1f * r * glm::vec3(-0.3f, 0.2f, 0.1f)};
        std::mt19937 rng(5);
        std::normal_distribution<float> n(0.f, 1.f);
        int segments = 0, blocked = 0;
        for (int i = 0; i < 3000; ++i) {
            const glm::vec3 o = c + 2.f * r * glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
            const Ray primary{o, glm::normalize(c + 0.3f * r * glm::vec3(n(rng), n(rng), n(rng)) - o)};
            Hit h;
            if (!tracer.closestHit(primary, {}, h)) continue;
            const SurfaceInteraction si = tracer.interaction(primary, h);
            const glm::vec3 light = lights[i % 2];
            const glm::vec3 so = offsetRayOrigin(si.position, si.positionError, si.geometricNormal,
                                                 light - si.position);
            const Ray shadow{so, light - so};
            RayQuery q;
            q.tMax = 1.f - 1e-4f;
            Hit sh;
            const bool fh = tracer.closestHit(shadow, q, sh);
            ASSERT_EQ(tracer.anyHit(shadow, q), fh) << "segment " << i;
            ++segments;
            blocked += fh;
        }
        EXPECT_GT(segments, 500);
        EXPECT_GT(blocked, 0);
    }
}

INSTANTIATE_TEST_SUITE_P(TracerGltf, TracerModels, ::testing::Values("Duck", "2CylinderEngine"));

} // namespace
} // namespace mvcl
