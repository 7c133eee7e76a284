#pragma once
// Private: the watertight ray/triangle kernel shared by intersectTriangle() and the tracer, so
// that the public test, the BVH and the brute-force oracle run literally the same arithmetic.

#include "KernelIsa.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include <glm/vec3.hpp>

#include <cmath>

namespace mvcl::detail {

/// Extra relative slack on the early tMax rejection. The early test compares t·det (rounded)
/// against tMax·det (rounded); the exact range check happens on the final t, so the early test
/// must never reject a triangle whose final t would pass. 2^-20 is ~8 ulps, far above the ~3 ulps
/// the product and the division can differ by.
inline constexpr float kEarlyRejectSlack = 1.f + 1.f / 1048576.f;

// Compiled into every kernel unit: one copy per instruction set (KernelIsa.h).
inline namespace MVCL_ISA_NAMESPACE {

/// Woop–Benthin–Wald watertight test, pbrt-v4 variant (shapes.cpp IntersectTriangle). Returns the
/// hit with t > 0 guaranteed (conservative t > δt) and t ≤ tMax (up to the slack above: callers
/// re-check the range on the returned t). Zero-area triangles never hit (det == 0).
/// max of non-negative finite values; std::fmax is a libm call because of its NaN rules.
inline float max3(float a, float b, float c) {
    const float m = a > b ? a : b;
    return m > c ? m : c;
}

/// The bound layer priority compares hits with (TriangleHit::tError), from the same error analysis
/// as δt below but for comparing two hits rather than proving t > 0. t is the mean of the z_i
/// weighted by e_i / det, and det is summed from the same rounded e_i, so an error εi of the edge
/// function ei moves t by Σ εi·(zi − t) / det: the edge functions' error δE weighs with the
/// triangle's depth spread Σ|zi − t|, not with its distance maxZt as in δt (which for a facet seen
/// from a few sizes away is a thousand ulps of t). The other terms: the zi (γ₃·maxZt), the
/// numerator's products and sums (γ₃·maxZt, as Σ|ei·zi| ≤ maxZt·|det| for a hit), det's sum and
/// the division (γ₃·t); all doubled for the second-order terms and the bound's own rounding.
/// The 4-wide kernel computes exactly these operations in this order.
inline float orderingError(float t, float maxZt, float deltaE, float spread, float absInvDet) {
    return 2.f * ((mulUnfused(gamma(3), 2.f * maxZt) + mulUnfused(gamma(3), std::fabs(t))) +
                  mulUnfused(mulUnfused(deltaE, spread), absInvDet));
}

inline bool watertightIntersect(const WatertightRay &r, const glm::vec3 &p0, const glm::vec3 &p1,
                                const glm::vec3 &p2, float tMax, TriangleHit &hit) {
    // Translate to the ray origin, permute so the ray's dominant axis is z, shear so the ray
    // becomes +z. Vertices are transformed independently of the triangle, so a vertex or edge
    // shared by two triangles gets bit-identical transformed values in both.
    // Every product that is later added to goes through mulUnfused(): with FMA contraction the
    // results would depend on the compiler and its flags (FloatBits.h).
    const float p0z = p0[r.kz] - r.origin[r.kz];
    const float p1z = p1[r.kz] - r.origin[r.kz];
    const float p2z = p2[r.kz] - r.origin[r.kz];
    const float p0x = (p0[r.kx] - r.origin[r.kx]) + mulUnfused(r.sx, p0z);
    const float p0y = (p0[r.ky] - r.origin[r.ky]) + mulUnfused(r.sy, p0z);
    const float p1x = (p1[r.kx] - r.origin[r.kx]) + mulUnfused(r.sx, p1z);
    const float p1y = (p1[r.ky] - r.origin[r.ky]) + mulUnfused(r.sy, p1z);
    const float p2x = (p2[r.kx] - r.origin[r.kx]) + mulUnfused(r.sx, p2z);
    const float p2y = (p2[r.ky] - r.origin[r.ky]) + mulUnfused(r.sy, p2z);

    // 2D edge functions. a·b − c·d without FMA contraction is exactly antisymmetric, so an edge
    // shared with opposite winding gets exactly the negated value.
    float e0 = mulUnfused(p1x, p2y) - mulUnfused(p1y, p2x);
    float e1 = mulUnfused(p2x, p0y) - mulUnfused(p2y, p0x);
    float e2 = mulUnfused(p0x, p1y) - mulUnfused(p0y, p1x);
    if (e0 == 0.f || e1 == 0.f || e2 == 0.f) {
        // The ray passes (within float precision) through an edge or vertex: decide the sign
        // exactly. Products of floats are exact in double, so a zero here is a true zero.
        e0 = float(double(p2y) * double(p1x) - double(p2x) * double(p1y));
        e1 = float(double(p0y) * double(p2x) - double(p0x) * double(p2y));
        e2 = float(double(p1y) * double(p0x) - double(p1x) * double(p0y));
    }
    if ((e0 < 0.f || e1 < 0.f || e2 < 0.f) && (e0 > 0.f || e1 > 0.f || e2 > 0.f)) return false;
    const float det = e0 + e1 + e2;
    if (det == 0.f) return false; // degenerate (zero projected area) or NaN-free miss

    const float z0 = r.sz * p0z;
    const float z1 = r.sz * p1z;
    const float z2 = r.sz * p2z;
    const float tScaled = mulUnfused(e0, z0) + mulUnfused(e1, z1) + mulUnfused(e2, z2);
    if (det < 0.f && (tScaled >= 0.f || tScaled < tMax * kEarlyRejectSlack * det)) return false;
    if (det > 0.f && (tScaled <= 0.f || tScaled > tMax * kEarlyRejectSlack * det)) return false;

    const float invDet = 1.f / det;
    const float t = tScaled * invDet;
    if (!(t > 0.f)) return false;

    // Conservative t > δt (pbrt-v4 §6.8.4): the hit is in front of the origin even counting
    // every rounding error above.
    const float maxZt = max3(std::fabs(z0), std::fabs(z1), std::fabs(z2));
    const float deltaZ = gamma(3) * maxZt;
    const float maxXt = max3(std::fabs(p0x), std::fabs(p1x), std::fabs(p2x));
    const float maxYt = max3(std::fabs(p0y), std::fabs(p1y), std::fabs(p2y));
    // The shear adds sx·pz to x (sy·pz to y), so their rounding is bounded by |sx|·max|pz|.
    // pbrt-v4 bounds it by maxZt instead (true for |d| ≤ 1, since |sx| ≤ 1), which for grazing
    // rays (|sx|, |sy| ≪ 1) is so loose that δt exceeds t and flat surfaces are missed below
    // ~3e-5 rad (catalogue case 10).
    const float maxPz = max3(std::fabs(p0z), std::fabs(p1z), std::fabs(p2z));
    const float deltaX = gamma(5) * (maxXt + mulUnfused(std::fabs(r.sx), maxPz));
    const float deltaY = gamma(5) * (maxYt + mulUnfused(std::fabs(r.sy), maxPz));
    const float deltaE =
        2.f * (unfused(gamma(2) * maxXt * maxYt) + mulUnfused(deltaY, maxXt) + mulUnfused(deltaX, maxYt));
    const float maxE = max3(std::fabs(e0), std::fabs(e1), std::fabs(e2));
    const float deltaT =
        3.f * (unfused(gamma(3) * maxE * maxZt) + mulUnfused(deltaE, maxZt) + mulUnfused(deltaZ, maxE)) *
        std::fabs(invDet);
    if (t <= deltaT) return false;

    hit.t = t;
    hit.tError = orderingError(t, maxZt, deltaE, std::fabs(z0 - t) + std::fabs(z1 - t) + std::fabs(z2 - t),
                               std::fabs(invDet));
    hit.b0 = e0 * invDet;
    hit.b1 = e1 * invDet;
    hit.b2 = e2 * invDet;
    return true;
}

} // namespace MVCL_ISA_NAMESPACE
} // namespace mvcl::detail
