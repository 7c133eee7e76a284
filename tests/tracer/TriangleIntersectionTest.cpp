#include <mvcl/tracer/TriangleIntersection.h>

#include "TracerTestUtil.h"

// The 4-wide kernel is private to the tracer; it is tested here against the scalar kernel.
#include "../../framework/src/tracer/WatertightTriangle4.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <bit>
#include <cfloat>
#include <string>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace mvcl {
namespace {

constexpr float kUlp1 = FLT_EPSILON; // one ulp at 1

TEST(TriangleIntersection, UnitRightTriangleAccuracy) {
    const glm::vec3 p0(0.f), p1(1.f, 0.f, 0.f), p2(0.f, 1.f, 0.f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(0.f, 1.f), off(-1.f, 1.f);
    int tested = 0;
    for (int i = 0; i < 20000; ++i) {
        const float u = uni(rng), v = uni(rng);
        if (u + v >= 0.999f || u < 1e-3f || v < 1e-3f) continue;
        const glm::vec3 target(u, v, 0.f);
        // Straight down (exact) and oblique (origin = target + offset, t = 1 exactly by construction
        // only up to rounding of the subtraction, so the oblique case uses a larger slack).
        Ray ray{target + glm::vec3(0.f, 0.f, 1.f), {0.f, 0.f, -1.f}};
        TriangleHit hit{};
        ASSERT_TRUE(intersectTriangle(ray, p0, p1, p2, 0.f, 10.f, hit)) << u << " " << v;
        EXPECT_LE(std::fabs(hit.t - 1.f), 16 * kUlp1);
        EXPECT_LE(std::fabs(hit.b1 - u), 16 * kUlp1);
        EXPECT_LE(std::fabs(hit.b2 - v), 16 * kUlp1);
        EXPECT_LE(std::fabs(hit.b0 - (1.f - u - v)), 16 * kUlp1);

        const glm::vec3 o = target + glm::vec3(off(rng), off(rng), 1.f);
        Ray oblique{o, target - o};
        ASSERT_TRUE(intersectTriangle(oblique, p0, p1, p2, 0.f, 10.f, hit));
        EXPECT_LE(std::fabs(hit.t - 1.f), 16 * kUlp1);
        EXPECT_LE(std::fabs(hit.b1 - u), 16 * kUlp1);
        EXPECT_LE(std::fabs(hit.b2 - v), 16 * kUlp1);
        ++tested;
    }
    EXPECT_GT(tested, 9000);
}

TEST(TriangleIntersection, HonoursTRange) {
    const glm::vec3 p0(0.f), p1(1.f, 0.f, 0.f), p2(0.f, 1.f, 0.f);
    const Ray ray{{0.25f, 0.25f, 2.f}, {0.f, 0.f, -1.f}};
    TriangleHit hit{};
    EXPECT_TRUE(intersectTriangle(ray, p0, p1, p2, 0.f, 3.f, hit));
    EXPECT_FLOAT_EQ(hit.t, 2.f);
    EXPECT_FALSE(intersectTriangle(ray, p0, p1, p2, 0.f, 1.5f, hit));
    EXPECT_FALSE(intersectTriangle(ray, p0, p1, p2, 2.5f, 3.f, hit));
    // Behind the origin: never, whatever the range says.
    const Ray away{{0.25f, 0.25f, 2.f}, {0.f, 0.f, 1.f}};
    EXPECT_FALSE(intersectTriangle(away, p0, p1, p2, -10.f, 10.f, hit));
    // Both windings hit.
    EXPECT_TRUE(intersectTriangle(ray, p0, p2, p1, 0.f, 3.f, hit));
}

TEST(TriangleIntersection, DegenerateTrianglesNeverHitAndNoNaN) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<std::array<glm::vec3, 3>> bad = {
        {glm::vec3(0.f), glm::vec3(0.f), glm::vec3(0.f)},                       // point
        {glm::vec3(0.f), glm::vec3(1.f, 1.f, 0.f), glm::vec3(2.f, 2.f, 0.f)},  // collinear
        {glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.f), glm::vec3(1.f, 0.f, 0.f)},  // repeated vertex
        {glm::vec3(0.f), glm::vec3(nan, 0.f, 0.f), glm::vec3(0.f, 1.f, 0.f)},  // NaN
        {glm::vec3(0.f), glm::vec3(inf, 0.f, 0.f), glm::vec3(0.f, 1.f, 0.f)},  // Inf
        {glm::vec3(-inf), glm::vec3(inf), glm::vec3(0.f, 1.f, 0.f)},           // Inf both ways
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(-2.f, 2.f);
    for (int i = 0; i < 20000; ++i) {
        const Ray ray{{uni(rng), uni(rng), uni(rng)}, {uni(rng), uni(rng), uni(rng)}};
        if (glm::length(ray.direction) == 0.f) continue;
        for (const auto &tri : bad) {
            TriangleHit hit{};
            EXPECT_FALSE(intersectTriangle(ray, tri[0], tri[1], tri[2], 0.f, inf, hit));
        }
        // Rays aimed straight along a collinear triangle's line.
        const Ray along{{-1.f, -1.f, 0.f}, {1.f, 1.f, 0.f}};
        TriangleHit hit{};
        EXPECT_FALSE(intersectTriangle(along, bad[1][0], bad[1][1], bad[1][2], 0.f, inf, hit));
    }
    // Valid triangle, every hit finite.
    const glm::vec3 p0(0.f), p1(1.f, 0.f, 0.f), p2(0.f, 1.f, 0.f);
    for (int i = 0; i < 20000; ++i) {
        const Ray ray{{uni(rng), uni(rng), uni(rng)}, {uni(rng), uni(rng), uni(rng)}};
        TriangleHit hit{};
        if (intersectTriangle(ray, p0, p1, p2, 0.f, inf, hit)) {
            EXPECT_TRUE(std::isfinite(hit.t) && std::isfinite(hit.b0) && std::isfinite(hit.b1) &&
                        std::isfinite(hit.b2));
            EXPECT_GT(hit.t, 0.f);
        }
    }
}

/// Rays from inside a closed tessellated sphere, aimed exactly at vertices or at edge midpoints,
/// must hit the mesh (Embree verify's WatertightTest, Woop 2013). The triangles around the target
/// are tried first; far from the origin, float quantisation folds the mesh, so the crossing may be
/// in another triangle: then every triangle is tried before a ray counts as a leak.
struct WatertightCase {
    glm::dvec3 center;
    bool edgeMidpoints;
};

/// Readable test names in ctest instead of a byte dump of the parameter.
[[maybe_unused]] void PrintTo(const WatertightCase &wc, std::ostream *os) {
    *os << "sphere at (" << wc.center.x << ", " << wc.center.y << ", " << wc.center.z << "), rays at "
        << (wc.edgeMidpoints ? "edge midpoints" : "vertices");
}

class TriangleWatertight : public ::testing::TestWithParam<WatertightCase> {};

TEST_P(TriangleWatertight, NoLeaksAtSharedEdgesAndVertices) {
    const WatertightCase wc = GetParam();
    const TriangleMesh mesh = test::makeUvSphere(wc.center, 2.0, 200, 200);
    // Triangles around each vertex.
    std::vector<std::vector<uint32_t>> fan(mesh.positions.size());
    for (uint32_t t = 0; t < mesh.indices.size(); ++t)
        for (int k = 0; k < 3; ++k) fan[mesh.indices[t][k]].push_back(t);

    std::mt19937 rng(1234);
    std::uniform_int_distribution<uint32_t> pickTri(0, uint32_t(mesh.indices.size() - 1));
    std::uniform_int_distribution<int> pickCorner(0, 2);
    std::uniform_real_distribution<double> inside(-0.5, 0.5);
    const int kRays = 100000;
    int leaks = 0;
    for (int r = 0; r < kRays; ++r) {
        const glm::uvec3 tri = mesh.indices[pickTri(rng)];
        const int k = pickCorner(rng);
        const uint32_t a = tri[k], b = tri[(k + 1) % 3];
        const glm::vec3 target = wc.edgeMidpoints
                                     ? 0.5f * (mesh.positions[a] + mesh.positions[b])
                                     : mesh.positions[a];
        const glm::vec3 origin(wc.center + glm::dvec3(inside(rng), inside(rng), inside(rng)));
        const Ray ray{origin, target - origin};
        const WatertightRay wray(ray);
        bool hitAny = false;
        auto tryFan = [&](uint32_t v) {
            for (uint32_t t : fan[v]) {
                const glm::uvec3 f = mesh.indices[t];
                TriangleHit hit{};
                if (intersectTriangle(wray, mesh.positions[f.x], mesh.positions[f.y],
                                      mesh.positions[f.z], 0.f,
                                      std::numeric_limits<float>::infinity(), hit)) {
                    EXPECT_TRUE(std::isfinite(hit.t));
                    hitAny = true;
                    return;
                }
            }
        };
        tryFan(a);
        if (!hitAny && wc.edgeMidpoints) tryFan(b);
        for (uint32_t t = 0; !hitAny && t < mesh.indices.size(); ++t) {
            const glm::uvec3 f = mesh.indices[t];
            TriangleHit hit{};
            hitAny = intersectTriangle(wray, mesh.positions[f.x], mesh.positions[f.y],
                                       mesh.positions[f.z], 0.f,
                                       std::numeric_limits<float>::infinity(), hit);
        }
        if (!hitAny) ++leaks;
    }
    EXPECT_EQ(leaks, 0) << "of " << kRays << " rays";
}

INSTANTIATE_TEST_SUITE_P(
    TriangleSphere200, TriangleWatertight,
    ::testing::Values(WatertightCase{{0.0, 0.0, 0.0}, false}, WatertightCase{{0.0, 0.0, 0.0}, true},
                      WatertightCase{{148376.0, 1234.0, -223423.0}, false},
                      WatertightCase{{148376.0, 1234.0, -223423.0}, true}),
    [](const ::testing::TestParamInfo<WatertightCase> &info) {
        return std::string(info.param.center.x == 0.0 ? "AtOrigin" : "FarAway") +
               (info.param.edgeMidpoints ? "EdgeMidpoints" : "Vertices");
    });

/// The 4-wide kernel must give bit-identical results to the scalar kernel on every lane: random
/// triangles, rays through shared vertices and edge midpoints (zero edge functions: the double
/// fallback), axis-aligned rays, degenerate triangles, far-away coordinates and finite tMax.
TEST(TriangleIntersection, FourWideKernelMatchesScalarBitwise) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> uni(-1.f, 1.f);
    std::uniform_int_distribution<int> pick(0, 7);
    const std::array<glm::vec3, 3> offsets = {glm::vec3(0.f), glm::vec3(148376.f, 1234.f, -223423.f),
                                              glm::vec3(1e-3f, -2e-3f, 5e-4f)};
    const glm::vec3 axes[3] = {{1.f, 0.f, 0.f}, {0.f, -1.f, 0.f}, {0.f, 0.f, 1.f}};
    int hits = 0, edgeHits = 0;
    for (int iter = 0; iter < 40000; ++iter) {
        const glm::vec3 off = offsets[std::size_t(iter) % offsets.size()];
        detail::PrimBlock block{};
        std::array<std::array<glm::vec3, 3>, 4> tris;
        for (int lane = 0; lane < 4; ++lane) {
            for (int k = 0; k < 3; ++k) tris[lane][k] = off + glm::vec3(uni(rng), uni(rng), uni(rng));
            const int kind = pick(rng);
            if (kind == 0) tris[lane][2] = tris[lane][1];                        // degenerate
            if (kind == 1 && lane > 0) tris[lane][0] = tris[lane - 1][1];        // shared vertex
            if (kind == 2 && lane > 0) {                                         // shared edge,
                tris[lane][0] = tris[lane - 1][1];                               // opposite winding
                tris[lane][1] = tris[lane - 1][0];
            }
            for (int k = 0; k < 3; ++k) block.setVertex(lane, k, tris[lane][k]);
        }
        const glm::vec3 origin = off + glm::vec3(uni(rng), uni(rng), uni(rng)) * 2.f;
        glm::vec3 target;
        switch (pick(rng) % 4) {
        case 0: target = tris[std::size_t(pick(rng) % 4)][std::size_t(pick(rng) % 3)]; break;
        case 1: {
            const auto &t = tris[std::size_t(pick(rng) % 4)];
            target = 0.5f * (t[0] + t[1]);
            break;
        }
        default: target = off + glm::vec3(uni(rng), uni(rng), uni(rng)) * 0.5f; break;
        }
        Ray ray{origin, target - origin};
        if (iter % 16 == 0) ray.direction = axes[std::size_t(iter / 16) % 3];
        if (ray.direction == glm::vec3(0.f)) continue;
        const float tMax = iter % 3 == 0 ? 0.5f + uni(rng) : std::numeric_limits<float>::infinity();
        const WatertightRay wray(ray);
        const detail::WatertightRay4 wray4(wray);
        detail::TriangleHit4 h4;
        const int lanes = 1 + iter % 15;
        const int bits = detail::watertightIntersect4(wray4, block, lanes, tMax, h4);
        // The any-hit form (no barycentrics) hits the same lanes at the same t.
        detail::TriangleHit4 t4;
        const int tBits = detail::watertightIntersect4<false>(wray4, block, lanes, tMax, t4);
        ASSERT_EQ(tBits, bits) << "iteration " << iter;
        for (int lane = 0; lane < 4; ++lane) {
            if ((bits >> lane) & 1) {
                EXPECT_EQ(std::bit_cast<uint32_t>(t4.t[lane]), std::bit_cast<uint32_t>(h4.t[lane]));
            }
        }
        for (int lane = 0; lane < 4; ++lane) {
            TriangleHit h;
            const bool scalar = (lanes >> lane) & 1 &&
                                detail::watertightIntersect(wray, tris[lane][0], tris[lane][1],
                                                            tris[lane][2], tMax, h);
            ASSERT_EQ(bool((bits >> lane) & 1), scalar) << "iteration " << iter << " lane " << lane;
            if (!scalar) continue;
            ++hits;
            edgeHits += h.b0 == 0.f || h.b1 == 0.f || h.b2 == 0.f;
            EXPECT_EQ(std::bit_cast<uint32_t>(h4.t[lane]), std::bit_cast<uint32_t>(h.t));
            EXPECT_EQ(std::bit_cast<uint32_t>(h4.b0[lane]), std::bit_cast<uint32_t>(h.b0));
            EXPECT_EQ(std::bit_cast<uint32_t>(h4.b1[lane]), std::bit_cast<uint32_t>(h.b1));
            EXPECT_EQ(std::bit_cast<uint32_t>(h4.b2[lane]), std::bit_cast<uint32_t>(h.b2));
        }
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(edgeHits, 10); // the double fallback was exercised
}

} // namespace
} // namespace mvcl
