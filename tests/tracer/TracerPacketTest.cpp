// Packet queries (Tracer::closestHits, Tracer::anyHits) against single rays on real glTF models:
// every packet variant this CPU has (AVX-512, AVX2), coherent 4×4 tiles of a camera and random
// rays, with t-ranges, layer masks, clip volumes, layer priority and exact equal-t ties. The
// packet results must be the single-ray ones bit for bit.

#include <mvcl/core/Error.h>
#include <mvcl/model/GltfLoader.h>
#include <mvcl/tracer/Tracer.h>

#include "../../framework/src/tracer/TraversalIsa.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace mvcl {
namespace {

using detail::PacketIsa;

Scene loadModel(const std::string &name) {
    return loadGltf(std::filesystem::path(MVCL_TEST_DATA_DIR) / "models" / name / (name + ".glb"));
}

/// The packet variants this CPU can run, widest first.
std::vector<PacketIsa> availablePacketIsas() {
    std::vector<PacketIsa> isas;
    if (detail::packetIsaAvailable() == PacketIsa::Avx512) isas.push_back(PacketIsa::Avx512);
    if (detail::packetIsaAvailable() >= PacketIsa::Avx2) isas.push_back(PacketIsa::Avx2);
    isas.push_back(PacketIsa::SingleRays);
    return isas;
}

const char *isaName(PacketIsa isa) {
    switch (isa) {
    case PacketIsa::Avx512: return "avx512";
    case PacketIsa::Avx2: return "avx2";
    case PacketIsa::SingleRays: break;
    }
    return "single rays";
}

std::unique_ptr<Tracer> buildTracer(const Scene &scene, PacketIsa isa) {
    detail::limitPacketIsa(isa);
    auto tracer = std::make_unique<Tracer>(scene);
    detail::limitPacketIsa(PacketIsa::Avx512);
    return tracer;
}

/// The mesh with the most triangles.
uint32_t largestMesh(const Scene &scene) {
    uint32_t largest = 0;
    for (uint32_t m = 0; m < scene.meshes.size(); ++m)
        if (scene.meshes[m].indices.size() > scene.meshes[largest].indices.size()) largest = m;
    return largest;
}

/// The model with a sphere and a ground plane added, its largest mesh duplicated at the end
/// (every hit on it an exact equal-t tie between two geometries) and, when `layered`, its meshes
/// spread over three layers so that closest hits run layer priority.
Scene testScene(const std::string &model, bool layered) {
    Scene scene = loadModel(model);
    const Bounds3f b = scene.bounds();
    scene.meshes.push_back(scene.meshes[largestMesh(scene)]);
    Sphere sphere;
    sphere.center = b.center() + 0.25f * b.extent();
    sphere.radius = 0.1f * glm::length(b.extent());
    scene.spheres.push_back(sphere);
    Plane ground;
    ground.offset = b.min.y - 0.01f * b.extent().y;
    scene.planes.push_back(ground);
    if (layered) {
        // The tied pair stays in layer 0, inside every query's mask.
        const uint32_t tied = largestMesh(scene);
        for (std::size_t m = 0; m + 1 < scene.meshes.size(); ++m) scene.meshes[m].layer = m == tied ? 0 : int(m % 3);
        scene.meshes.back().layer = 0;
        scene.spheres.front().layer = 1;
    }
    return scene;
}

/// Rays in packets of up to 16.
using Packet = std::vector<Ray>;

/// The primary rays of a W×H pinhole image of the scene, grouped in 4×4 tiles (edge tiles partial).
std::vector<Packet> tilePackets(const Scene &scene, int width, int height, const glm::vec3 &view) {
    const Bounds3f b = scene.bounds();
    const glm::vec3 center = b.center();
    const float radius = 0.5f * glm::length(b.extent());
    const glm::vec3 eye = center + 2.2f * radius * glm::normalize(view);
    const glm::vec3 forward = glm::normalize(center - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.f, 1.f, 0.f)));
    const glm::vec3 up = glm::cross(right, forward);
    const float tanHalf = std::tan(0.35f);
    std::vector<Packet> packets;
    for (int ty = 0; ty < height; ty += 4)
        for (int tx = 0; tx < width; tx += 4) {
            Packet p;
            for (int y = ty; y < std::min(ty + 4, height); ++y)
                for (int x = tx; x < std::min(tx + 4, width); ++x) {
                    const float sx = (2.f * (float(x) + 0.5f) / float(width) - 1.f) * tanHalf;
                    const float sy = (1.f - 2.f * (float(y) + 0.5f) / float(height)) * tanHalf;
                    p.push_back({eye, glm::normalize(forward + sx * right + sy * up)});
                }
            packets.push_back(p);
        }
    return packets;
}

/// Incoherent packets: random origins around and inside the bounds, random directions (mixed
/// octants), packet sizes 1..16, with an invalid ray now and then.
std::vector<Packet> randomPackets(const Scene &scene, int count, uint32_t seed) {
    const Bounds3f b = scene.bounds();
    const glm::vec3 c = b.center();
    const float r = 0.5f * glm::length(b.extent());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uni(0.f, 1.f);
    std::normal_distribution<float> n(0.f, 1.f);
    std::vector<Packet> packets;
    for (int k = 0; k < count; ++k) {
        Packet p;
        const int size = 1 + k % Tracer::kPacketSize;
        for (int i = 0; i < size; ++i) {
            const glm::vec3 target = b.min + glm::vec3{uni(rng), uni(rng), uni(rng)} * b.extent();
            const glm::vec3 o = (i % 3 == 2) ? b.min + glm::vec3{uni(rng), uni(rng), uni(rng)} * b.extent()
                                             : c + 2.f * r * glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
            Ray ray{o, glm::normalize(target - o)};
            if (i == 7 && k % 5 == 0) ray.direction = glm::vec3(std::numeric_limits<float>::quiet_NaN());
            p.push_back(ray);
        }
        packets.push_back(p);
    }
    return packets;
}

/// The queries each packet is traced with: default, a t-range, a layer mask and clip volumes.
std::vector<RayQuery> testQueries(const Scene &scene) {
    const Bounds3f b = scene.bounds();
    const float r = 0.5f * glm::length(b.extent());
    std::vector<RayQuery> queries(5);
    queries[1].tMin = 1.9f * r;
    queries[1].tMax = 2.6f * r;
    queries[2].layerMask = 0b101;
    queries[3].addClip(ClipVolume::box(b.min, b.center(), ClipVolume::Keep::Outside));
    queries[3].addClip(ClipVolume::halfSpace(glm::vec3(0.3f, 1.f, 0.1f), glm::dot(glm::vec3(0.3f, 1.f, 0.1f), b.center()) + 0.2f * r,
                                             ClipVolume::Keep::Outside));
    queries[4].addClip(ClipVolume::sphere(b.center(), 0.6f * r, ClipVolume::Keep::Inside));
    queries[4].tMax = 2.4f * r;
    return queries;
}

struct Counts {
    int hits = 0;
    int ties = 0;     ///< hits whose winner has an exact equal-t twin (the duplicated mesh)
    int occluded = 0;
    int occludedWithin = 0; ///< occluded within the per-ray ranges
};

/// Every packet through closestHits and anyHits against closestHit and anyHit ray by ray.
void expectSameAsSingleRays(const Tracer &packets, const Tracer &single, const std::vector<Packet> &set,
                            const RayQuery &query, uint32_t tiedGeometry, uint32_t duplicatedGeometry,
                            Counts &counts) {
    for (std::size_t k = 0; k < set.size(); ++k) {
        const Packet &p = set[k];
        std::array<Hit, Tracer::kPacketSize> hits{};
        const uint32_t found = packets.closestHits(p, query, hits);
        const uint32_t occluded = packets.anyHits(p, query);
        // Per-ray ranges (shadow rays toward a point light): each ray ends just before, exactly
        // at or just past its own closest hit, or at a fixed distance where it has none.
        std::array<float, Tracer::kPacketSize> tMax{};
        for (std::size_t i = 0; i < p.size(); ++i) {
            Hit h;
            const float t = single.closestHit(p[i], query, h) ? h.t : 1.f;
            tMax[i] = i % 3 == 0 ? std::nextafter(t, 0.f) : i % 3 == 1 ? t : 2.f * t;
        }
        const uint32_t occludedWithin = packets.anyHits(p, query, {tMax.data(), p.size()});
        for (std::size_t i = 0; i < p.size(); ++i) {
            Hit h;
            const bool expected = single.closestHit(p[i], query, h);
            ASSERT_EQ(bool((found >> i) & 1u), expected) << "packet " << k << " ray " << i;
            ASSERT_EQ(bool((occluded >> i) & 1u), single.anyHit(p[i], query)) << "packet " << k << " ray " << i;
            RayQuery within = query;
            within.tMax = std::min(query.tMax, tMax[i]);
            ASSERT_EQ(bool((occludedWithin >> i) & 1u), single.anyHit(p[i], within)) << "packet " << k << " ray " << i;
            ASSERT_EQ(single.anyHit(p[i], query, tMax[i]), single.anyHit(p[i], within)) << "packet " << k << " ray " << i;
            counts.occluded += (occluded >> i) & 1u;
            counts.occludedWithin += (occludedWithin >> i) & 1u;
            if (!expected) continue;
            ++counts.hits;
            const Hit &g = hits[i];
            ASSERT_EQ(std::bit_cast<uint32_t>(g.t), std::bit_cast<uint32_t>(h.t)) << "packet " << k << " ray " << i;
            ASSERT_EQ(std::bit_cast<uint32_t>(g.u), std::bit_cast<uint32_t>(h.u)) << "packet " << k << " ray " << i;
            ASSERT_EQ(std::bit_cast<uint32_t>(g.v), std::bit_cast<uint32_t>(h.v)) << "packet " << k << " ray " << i;
            ASSERT_EQ(g.kind, h.kind) << "packet " << k << " ray " << i;
            ASSERT_EQ(g.layer, h.layer) << "packet " << k << " ray " << i;
            ASSERT_EQ(g.geometry, h.geometry) << "packet " << k << " ray " << i;
            ASSERT_EQ(g.primitive, h.primitive) << "packet " << k << " ray " << i;
            // The tie-break keeps the original (lower) geometry; its duplicate never wins.
            ASSERT_NE(g.geometry, duplicatedGeometry) << "packet " << k << " ray " << i;
            counts.ties += g.kind == GeometryKind::Triangle && g.geometry == tiedGeometry;
        }
    }
}

class TracerPackets : public ::testing::TestWithParam<std::string> {};

TEST_P(TracerPackets, PacketsMatchSingleRays) {
    for (const bool layered : {false, true}) {
        SCOPED_TRACE(layered ? "three layers" : "one layer");
        const Scene scene = testScene(GetParam(), layered);
        const uint32_t duplicate = uint32_t(scene.meshes.size() - 1);
        const uint32_t tied = largestMesh(scene);
        std::vector<Packet> coherent = tilePackets(scene, 50, 38, {0.6f, 0.45f, 0.75f});
        const std::vector<Packet> grazing = tilePackets(scene, 30, 30, {-1.f, 0.02f, 0.f});
        coherent.insert(coherent.end(), grazing.begin(), grazing.end());
        const std::vector<Packet> incoherent = randomPackets(scene, 160, 7);
        const Tracer single(scene);
        for (const PacketIsa isa : availablePacketIsas()) {
            SCOPED_TRACE(isaName(isa));
            const auto packets = buildTracer(scene, isa);
            EXPECT_STREQ(packets->packetIsa(), isaName(isa));
            for (const RayQuery &query : testQueries(scene)) {
                Counts coherentCounts, incoherentCounts;
                expectSameAsSingleRays(*packets, single, coherent, query, tied, duplicate, coherentCounts);
                expectSameAsSingleRays(*packets, single, incoherent, query, tied, duplicate, incoherentCounts);
                // The sets must exercise hits, misses, ties and occlusion under every query.
                EXPECT_GT(coherentCounts.hits, 100);
                EXPECT_GT(coherentCounts.ties, 0);
                EXPECT_GT(incoherentCounts.hits, 50);
                EXPECT_GT(incoherentCounts.occluded, 50);
                // Some rays end before their hit: the per-ray ranges must remove occlusions.
                EXPECT_GT(coherentCounts.occludedWithin, 0);
                EXPECT_LT(coherentCounts.occludedWithin, coherentCounts.occluded);
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(TracerGltf, TracerPackets, ::testing::Values("Duck", "2CylinderEngine"));

TEST(TracerPacketsTest, RejectsOversizedPackets) {
    Scene scene = loadModel("Box");
    const Tracer tracer(scene);
    std::vector<Ray> rays(Tracer::kPacketSize + 1);
    std::vector<Hit> hits(rays.size());
    EXPECT_THROW(tracer.closestHits(rays, RayQuery{}, hits), Error);
    EXPECT_THROW(tracer.anyHits(rays, RayQuery{}), Error);
    const std::vector<float> ranges(3, 1.f);
    EXPECT_THROW(tracer.anyHits(std::span<const Ray>(rays.data(), 4), RayQuery{}, ranges), Error);
    std::vector<Hit> tooFew(3);
    EXPECT_THROW(tracer.closestHits(std::span<const Ray>(rays.data(), 4), RayQuery{}, tooFew), Error);
    EXPECT_EQ(tracer.closestHits({}, RayQuery{}, {}), 0u);
}

} // namespace
} // namespace mvcl
