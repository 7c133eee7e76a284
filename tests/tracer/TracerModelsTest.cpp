// BVH against brute force on real glTF models (the loader's output, so real topology, shared
// vertices, slivers and duplicates).

#include <mvcl/model/GltfLoader.h>
#include <mvcl/tracer/Tracer.h>

#include "../../framework/src/tracer/TraversalIsa.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <bit>
#include <filesystem>
#include <random>
#include <string>

namespace mvcl {
namespace {

class TracerModels : public ::testing::TestWithParam<std::string> {};

TEST_P(TracerModels, BvhMatchesBruteForce) {
    const std::filesystem::path path =
        std::filesystem::path(MVCL_TEST_DATA_DIR) / "models" / GetParam() / (GetParam() + ".glb");
    const Scene scene = loadGltf(path);
    // Both traversal variants (AVX2 where available, and the SSE baseline) against the oracle.
    for (const bool forceSse : {false, true}) {
        SCOPED_TRACE(forceSse ? "SSE traversal" : "default traversal");
        detail::forceSseTraversal(forceSse);
        const Tracer tracer(scene);
        detail::forceSseTraversal(false);
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
            const glm::vec3 target = b.min + glm::vec3(uni(rng), uni(rng), uni(rng)) * b.extent();
            glm::vec3 o;
            if (i % 3 == 2) o = b.min + glm::vec3(uni(rng), uni(rng), uni(rng)) * b.extent();
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

INSTANTIATE_TEST_SUITE_P(TracerGltf, TracerModels, ::testing::Values("Duck", "2CylinderEngine"));

} // namespace
} // namespace mvcl
