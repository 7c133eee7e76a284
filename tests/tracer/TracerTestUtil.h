#pragma once
// Procedural geometry and comparisons shared by the tracer tests.

#include <mvcl/model/Scene.h>
#include <mvcl/model/TriangleMesh.h>
#include <mvcl/tracer/Tracer.h>

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <glm/vec3.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace mvcl::test {

/// A uniformly random unit vector.
inline glm::vec3 randomUnit(std::mt19937 &rng) {
    std::normal_distribution<float> n(0.f, 1.f);
    for (;;) {
        const glm::vec3 v{n(rng), n(rng), n(rng)};
        const float len = glm::length(v);
        if (len > 1e-3f) return v / len;
    }
}

/// Bitwise equality of two hits (t compared as bits so −0/NaN subtleties cannot hide).
inline void expectSameHit(bool foundA, const Hit &a, bool foundB, const Hit &b, const std::string &what) {
    ASSERT_EQ(foundA, foundB) << what;
    if (!foundA) return;
    EXPECT_EQ(std::bit_cast<uint32_t>(a.t), std::bit_cast<uint32_t>(b.t)) << what << " " << a.t << " vs " << b.t;
    EXPECT_EQ(a.kind, b.kind) << what;
    EXPECT_EQ(a.geometry, b.geometry) << what;
    EXPECT_EQ(a.primitive, b.primitive) << what;
    EXPECT_EQ(std::bit_cast<uint32_t>(a.u), std::bit_cast<uint32_t>(b.u)) << what;
    EXPECT_EQ(std::bit_cast<uint32_t>(a.v), std::bit_cast<uint32_t>(b.v)) << what;
    EXPECT_EQ(a.layer, b.layer) << what;
}

/// Random triangles in [-1, 1]³ plus exact duplicates, axis-aligned and oblique coplanar sets,
/// spheres and a floor plane, spread over four layers.
inline Scene makeSoup(int triangles, uint32_t seed) {
    Scene scene;
    scene.materials.resize(1);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.f, 1.f), small(-0.2f, 0.2f);
    for (int layer = 0; layer < 4; ++layer) {
        TriangleMesh mesh;
        mesh.name = "soup" + std::to_string(layer);
        mesh.layer = layer;
        for (int i = 0; i < triangles / 4; ++i) {
            const glm::vec3 c{pos(rng), pos(rng), pos(rng)};
            const uint32_t base = uint32_t(mesh.positions.size());
            const int kind = i % 8;
            if (kind == 0 && i > 0) {
                // Exact duplicate of the previous triangle (same vertices, new indices).
                const glm::uvec3 prev = mesh.indices.back();
                mesh.positions.push_back(mesh.positions[prev.x]);
                mesh.positions.push_back(mesh.positions[prev.y]);
                mesh.positions.push_back(mesh.positions[prev.z]);
            } else if (kind == 1) {
                // Coplanar with z = 0.25 (axis-aligned: box faces coincide with the plane).
                mesh.positions.push_back({c.x, c.y, 0.25f});
                mesh.positions.push_back({c.x + small(rng), c.y + small(rng), 0.25f});
                mesh.positions.push_back({c.x + small(rng), c.y + small(rng), 0.25f});
            } else if (kind == 2) {
                // Coplanar with the oblique plane x + y + z = 0.5.
                for (int k = 0; k < 3; ++k) {
                    const float x = c.x + small(rng), y = c.y + small(rng);
                    mesh.positions.push_back({x, y, 0.5f - x - y});
                }
            } else {
                for (int k = 0; k < 3; ++k)
                    mesh.positions.push_back(c + glm::vec3{small(rng), small(rng), small(rng)});
            }
            mesh.indices.push_back({base, base + 1, base + 2});
        }
        scene.meshes.push_back(std::move(mesh));
    }
    // A few degenerate and non-finite triangles that must be left out.
    TriangleMesh junk;
    junk.name = "junk";
    junk.positions = {glm::vec3(0.f), glm::vec3(0.5f), glm::vec3(1.f),
                      glm::vec3(std::numeric_limits<float>::quiet_NaN()), glm::vec3(0.1f, 0.f, 0.f)};
    junk.indices = {{0, 1, 2}, {0, 3, 4}, {0, 0, 4}};
    scene.meshes.push_back(std::move(junk));
    for (int i = 0; i < 8; ++i) {
        Sphere s;
        s.center = {pos(rng), pos(rng), pos(rng)};
        s.radius = 0.05f + 0.1f * std::fabs(small(rng));
        s.layer = i % 4;
        scene.spheres.push_back(s);
    }
    Sphere dup = scene.spheres.front(); // exact duplicate sphere
    scene.spheres.push_back(dup);
    Plane floor;
    floor.normal = {0.f, 1.f, 0.f};
    floor.offset = -1.5f;
    floor.layer = 2;
    scene.planes.push_back(floor);
    return scene;
}


/// A query with, at random, a layer mask over four layers, a distance window and up to three
/// clip volumes (boxes, spheres, half-spaces; keep inside or outside) in [−1, 1]³.
inline RayQuery randomQuery(std::mt19937 &rng) {
    RayQuery q;
    std::uniform_int_distribution<int> coin(0, 3);
    std::uniform_real_distribution<float> uni(0.f, 1.f), pos(-1.f, 1.f);
    if (coin(rng) == 0) q.layerMask = uint32_t(rng()) & 0xfu;
    if (coin(rng) == 0) {
        q.tMin = 2.f * uni(rng);
        q.tMax = q.tMin + 2.f * uni(rng);
    }
    const int clips = coin(rng) == 0 ? 1 + coin(rng) % 3 : 0;
    for (int i = 0; i < clips; ++i) {
        const int shape = coin(rng) % 3;
        const ClipVolume::Keep keep = coin(rng) % 2 ? ClipVolume::Keep::Inside : ClipVolume::Keep::Outside;
        const glm::vec3 a{pos(rng), pos(rng), pos(rng)};
        const glm::vec3 b = a + glm::vec3{uni(rng), uni(rng), uni(rng)};
        const float radius = uni(rng);
        if (shape == 0) q.addClip(ClipVolume::box(a, b, keep));
        if (shape == 1) q.addClip(ClipVolume::sphere(a, radius, keep));
        if (shape == 2) q.addClip(ClipVolume::halfSpace(randomUnit(rng), radius, keep));
    }
    return q;
}

/// Closed UV sphere: `rings` latitude bands × `segments` longitudes, one vertex per pole.
/// Positions are computed in double around the origin and then offset by `center` in double, so a
/// far-away sphere gets the (quantised) float positions a loader would produce.
inline TriangleMesh makeUvSphere(const glm::dvec3 &center, double radius, int rings, int segments) {
    TriangleMesh mesh;
    mesh.name = "uv-sphere";
    auto add = [&](const glm::dvec3 &p) {
        mesh.positions.push_back(glm::vec3(center + p));
        mesh.normals.push_back(glm::vec3(p / radius));
        return uint32_t(mesh.positions.size() - 1);
    };
    const uint32_t north = add({0.0, 0.0, radius});
    std::vector<uint32_t> ring;
    for (int i = 1; i < rings; ++i) {
        const double theta = std::numbers::pi * double(i) / double(rings);
        for (int j = 0; j < segments; ++j) {
            const double phi = 2.0 * std::numbers::pi * double(j) / double(segments);
            ring.push_back(add({radius * std::sin(theta) * std::cos(phi),
                                radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta)}));
        }
    }
    const uint32_t south = add({0.0, 0.0, -radius});
    auto at = [&](int i, int j) { return ring[std::size_t(i) * segments + (j % segments)]; };
    for (int j = 0; j < segments; ++j) mesh.indices.push_back({north, at(0, j), at(0, j + 1)});
    for (int i = 0; i + 1 < rings - 1; ++i)
        for (int j = 0; j < segments; ++j) {
            mesh.indices.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.indices.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    for (int j = 0; j < segments; ++j)
        mesh.indices.push_back({at(rings - 2, j), south, at(rings - 2, j + 1)});
    return mesh;
}

/// Axis-aligned box [lo, hi] as 12 outward-wound triangles.
inline TriangleMesh makeBoxMesh(const glm::vec3 &lo, const glm::vec3 &hi) {
    TriangleMesh mesh;
    mesh.name = "box";
    for (int i = 0; i < 8; ++i)
        mesh.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    const uint32_t f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                              {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &q : f) {
        mesh.indices.push_back({q[0], q[1], q[2]});
        mesh.indices.push_back({q[0], q[2], q[3]});
    }
    return mesh;
}

/// `rays` random rays from outside a's scene bounds into them, every other one under layer
/// mask 0b10, get the same closest hits from both tracers; at least a tenth of them hit.
inline void expectSameClosestHits(const Tracer &a, const Tracer &b, int rays = 1000) {
    const Bounds3f bounds = a.scene().bounds();
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    int hits = 0;
    for (int i = 0; i < rays; ++i) {
        const glm::vec3 origin = bounds.min - (bounds.max - bounds.min);
        const glm::vec3 target = glm::mix(bounds.min, bounds.max, glm::vec3(unit(rng), unit(rng), unit(rng)));
        const Ray ray{origin, glm::normalize(target - origin)};
        RayQuery query;
        query.layerMask = i % 2 ? ~0u : 0b10u;
        Hit ha, hb;
        const bool fa = a.closestHit(ray, query, ha);
        ASSERT_EQ(fa, b.closestHit(ray, query, hb));
        if (!fa) continue;
        ++hits;
        EXPECT_EQ(ha.t, hb.t);
        EXPECT_EQ(ha.geometry, hb.geometry);
        EXPECT_EQ(ha.primitive, hb.primitive);
        EXPECT_EQ(ha.layer, hb.layer);
    }
    EXPECT_GT(hits, rays / 10);
}

} // namespace mvcl::test
