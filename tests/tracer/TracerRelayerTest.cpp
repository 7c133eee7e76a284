// Tracer(scene, sameGeometry): a tracer moved onto new layers answers every query as a tracer
// built from scratch over the relayered scene.

#include "TracerTestUtil.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <random>
#include <vector>

using namespace mvcl;

namespace {

/// Forty small spheres of triangles around the origin, two analytic spheres and a plane, all on
/// layer 0: enough nodes for the packet kernels, several meshes to move between layers.
Scene scatteredScene() {
    Scene s;
    s.materials.push_back(Material{});
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> pos(-4.0, 4.0), radius(0.3, 1.2);
    for (int i = 0; i < 40; ++i)
        s.meshes.push_back(test::makeUvSphere({pos(rng), pos(rng), pos(rng)}, radius(rng), 8, 12));
    Sphere big, small;
    big.radius = 2.5f;
    small.center = glm::vec3(3.f, 0.f, 0.f);
    small.radius = 0.7f;
    s.spheres = {big, small};
    Plane floor;
    floor.offset = 5.f;
    s.planes.push_back(floor);
    return s;
}

/// The same scene with every mesh, sphere and plane on a layer of its own choosing (0–5).
Scene relayered(const Scene &scene) {
    Scene s = scene;
    for (std::size_t i = 0; i < s.meshes.size(); ++i) s.meshes[i].layer = int(i % 6);
    s.spheres[0].layer = 2;
    s.spheres[1].layer = 5;
    s.planes[0].layer = 3;
    for (int layer = 0; layer < 6; ++layer) s.layers.ensure(layer);
    return s;
}

} // namespace

TEST(TracerRelayer, AnswersAsAFreshBuildOverTheNewLayers) {
    const Scene asRead = scatteredScene();
    const Tracer first(asRead);
    const Scene moved = relayered(asRead);
    const Tracer reused(moved, first);
    const Tracer fresh(moved);
    EXPECT_EQ(reused.buildStats().nodes, fresh.buildStats().nodes);
    EXPECT_EQ(reused.buildStats().triangles, fresh.buildStats().triangles);

    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-8.f, 8.f);
    std::uniform_int_distribution<uint32_t> mask(0, 63);
    int hits = 0, layeredMisses = 0;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 origin(coord(rng), coord(rng), coord(rng));
        const glm::vec3 direction = glm::normalize(glm::vec3(coord(rng), coord(rng), coord(rng)) - origin);
        RayQuery query;
        query.layerMask = i % 4 == 0 ? ~0u : mask(rng);
        Hit a, b;
        const bool foundA = reused.closestHit({origin, direction}, query, a);
        const bool foundB = fresh.closestHit({origin, direction}, query, b);
        test::expectSameHit(foundA, a, foundB, b, "ray " + std::to_string(i));
        hits += foundA;
        // The same ray with all layers hits, but not with this mask: the masks were refreshed.
        Hit any;
        if (!foundA && fresh.closestHit({origin, direction}, RayQuery{}, any)) ++layeredMisses;
        EXPECT_EQ(reused.anyHit({origin, direction}, query), fresh.anyHit({origin, direction}, query));
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(layeredMisses, 100);
}

TEST(TracerRelayer, PacketQueriesAgree) {
    const Scene asRead = scatteredScene();
    const Tracer first(asRead);
    const Scene moved = relayered(asRead);
    const Tracer reused(moved, first);
    const Tracer fresh(moved);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> jitter(-0.2f, 0.2f);
    for (int packet = 0; packet < 200; ++packet) {
        std::vector<Ray> rays;
        const glm::vec3 origin(0.f, 0.5f, 12.f);
        for (int k = 0; k < Tracer::kPacketSize; ++k)
            rays.push_back({origin, glm::normalize(glm::vec3(0.05f * float(packet % 20 - 10) + jitter(rng),
                                                             0.05f * float(packet / 20 - 5) + jitter(rng), -1.f))});
        RayQuery query;
        query.layerMask = packet % 2 ? 0b101101u : ~0u;
        std::vector<Hit> a(rays.size()), b(rays.size());
        const uint32_t foundA = reused.closestHits(rays, query, a);
        const uint32_t foundB = fresh.closestHits(rays, query, b);
        ASSERT_EQ(foundA, foundB);
        for (std::size_t k = 0; k < rays.size(); ++k)
            test::expectSameHit((foundA >> k) & 1u, a[k], (foundB >> k) & 1u, b[k], "packet lane " + std::to_string(k));
        EXPECT_EQ(reused.anyHits(rays, query), fresh.anyHits(rays, query));
    }
}

TEST(TracerRelayer, RefusesOtherGeometry) {
    const Scene asRead = scatteredScene();
    const Tracer first(asRead);
    Scene fewer = asRead;
    fewer.meshes.pop_back();
    EXPECT_THROW(Tracer(fewer, first), Error);
    Scene smaller = asRead;
    smaller.meshes[3].indices.pop_back();
    EXPECT_THROW(Tracer(smaller, first), Error);
}
