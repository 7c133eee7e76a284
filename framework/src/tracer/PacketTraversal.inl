#pragma once
// Private: packet traversal of the wide BVH, 16 rays at once (a 4×4 tile of coherent rays),
// compiled by two translation units: PacketAvx2.cpp (MVCL_PACKET_AVX512 0, built with -mavx2: the
// 16 rays as two 8-lane halves) and PacketAvx512.cpp (MVCL_PACKET_AVX512 1, built with -mavx512f:
// one 16-lane register). Each exports the packet's entry (loadPacket: the rays into lanes) and the
// walk as a table (KernelTables.h) and a Tracer picks one at run time. Everything here lands in
// the unit's own namespace (KernelIsa.h).
//
// Each child box is tested against all rays of the packet (ray lanes, not child lanes), with the
// arithmetic of intersectBox() lane by lane: same operands, same order, same NaN rule. A ray
// enters every box its own single-ray traversal could need, so the nearest hit in the total order
// of hitPrecedes() (and layer priority's window, a function of the candidate set) is found
// whatever order the packet visits the leaves in: the results are those of Tracer::closestHit()
// bit for bit. Leaves run the watertight test with the rays in the lanes (one triangle against
// all rays: intersectAcrossRays, the 4-wide kernel's operations per ray and triangle, with the
// error bound layer priority orders by), or ray by ray through the single-ray kernels: leaves
// that few rays reach (watertightIntersect4) and leaves holding spheres (testLeaf). Either way
// every t, barycentric and bound is the single-ray arithmetic.
//
// Each walk shares one near/far slab choice: tracePacket() splits the rays by direction octant.

#if !defined(MVCL_PACKET_AVX512)
#error "the including unit chooses the variant: MVCL_PACKET_AVX512 0 or 1"
#endif

#include "KernelIsa.h"
#include "LeafIntersection.h"
#include "PacketRays.h"
#include "PacketSetup.h"
#include "RayContext.h"
#include "WatertightTriangle.h"
#include "WideBvh.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <immintrin.h>

namespace mvcl::detail {
inline namespace MVCL_ISA_NAMESPACE {

/// Sixteen floats, one per ray of the packet.
struct Lanes {
#if MVCL_PACKET_AVX512
    __m512 v;
    static Lanes load(const float *p) { return {_mm512_load_ps(p)}; }
    static Lanes all(float x) { return {_mm512_set1_ps(x)}; }
    /// Lanes 0–7 from `lo`, 8–15 from `hi`.
    static Lanes join(__m256 lo, __m256 hi) {
        // The zero-masked insert with every lane set is the plain instruction (see max() below).
        return {_mm512_castpd_ps(_mm512_maskz_insertf64x4(__mmask8(0xff), _mm512_castps_pd(_mm512_castps256_ps512(lo)),
                                                          _mm256_castps_pd(hi), 1))};
    }
    /// p[i] in the lanes of `bits`, 0 elsewhere; nothing is read outside those lanes.
    static Lanes loadSome(unsigned bits, const float *p) { return {_mm512_maskz_loadu_ps(__mmask16(bits), p)}; }
    void store(float *p) const { _mm512_store_ps(p, v); }
#else
    __m256 lo, hi;
    static Lanes load(const float *p) { return {_mm256_load_ps(p), _mm256_load_ps(p + 8)}; }
    static Lanes all(float x) { return {_mm256_set1_ps(x), _mm256_set1_ps(x)}; }
    static Lanes join(__m256 lo, __m256 hi) { return {lo, hi}; }
    static Lanes loadSome(unsigned bits, const float *p);
    void store(float *p) const {
        _mm256_store_ps(p, lo);
        _mm256_store_ps(p + 8, hi);
    }
#endif
};

#if MVCL_PACKET_AVX512
inline Lanes sub(Lanes a, Lanes b) { return {_mm512_sub_ps(a.v, b.v)}; }
inline Lanes mul(Lanes a, Lanes b) { return {_mm512_mul_ps(a.v, b.v)}; }
inline Lanes div(Lanes a, Lanes b) { return {_mm512_div_ps(a.v, b.v)}; }
inline Lanes add(Lanes a, Lanes b) { return {_mm512_add_ps(a.v, b.v)}; }
/// The sign bit cleared / flipped (exact, as fabs and unary minus).
inline Lanes abs(Lanes a) {
    return {_mm512_castsi512_ps(_mm512_and_si512(_mm512_castps_si512(a.v), _mm512_set1_epi32(0x7fffffff)))};
}
inline Lanes negate(Lanes a) {
    return {_mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a.v), _mm512_set1_epi32(int(0x80000000u))))};
}
/// Bit i: a[i] P b[i] for the _CMP_ predicate P.
template <int P>
inline unsigned compare(Lanes a, Lanes b) { return _mm512_cmp_ps_mask(a.v, b.v, P); }
/// a·b rounded on its own, never fused with a following add (FloatBits.h, unfused()).
inline Lanes mulUnfused(Lanes a, Lanes b) {
    __m512 v = _mm512_mul_ps(a.v, b.v);
    __asm__("" : "+v"(v));
    return {v};
}
/// a in the lanes of `bits`, b elsewhere.
inline Lanes select(unsigned bits, Lanes a, Lanes b) { return {_mm512_mask_mov_ps(b.v, __mmask16(bits), a.v)}; }
/// Bit i: the sign bit of a[i] is set.
inline unsigned signBits(Lanes a) {
    const __m512i bits = _mm512_castps_si512(a.v);
    return _mm512_test_epi32_mask(bits, _mm512_set1_epi32(int(0x80000000u)));
}
// vmaxps/vminps return the second operand when either is NaN, as in intersectBox. The zero-masked
// forms with every lane set are the plain instruction; GCC 12's _mm512_max_ps passes an
// "undefined" source that -Wmaybe-uninitialized reports.
inline Lanes max(Lanes a, Lanes b) { return {_mm512_maskz_max_ps(__mmask16(0xffff), a.v, b.v)}; }
inline Lanes min(Lanes a, Lanes b) { return {_mm512_maskz_min_ps(__mmask16(0xffff), a.v, b.v)}; }
/// Bit i: a[i] <= b[i] (false for NaN).
inline unsigned lessEqual(Lanes a, Lanes b) { return _mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ); }
/// a in the lanes of `bits`, NaN elsewhere (a NaN entry distance never passes lessEqual).
inline Lanes keep(unsigned bits, Lanes a) {
    return {_mm512_mask_mov_ps(_mm512_set1_ps(std::numeric_limits<float>::quiet_NaN()), __mmask16(bits), a.v)};
}
/// Smallest lane of `bits` (not empty).
inline float minimum(unsigned bits, Lanes a) {
    // By hand, zero-masked forms throughout (see max()): _mm512_mask_reduce_min_ps trips the
    // same warning.
    constexpr __mmask16 all = 0xffff;
    __m512 m = _mm512_mask_mov_ps(_mm512_set1_ps(kInfinity), __mmask16(bits), a.v);
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_shuffle_f32x4(all, m, m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_shuffle_f32x4(all, m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_permute_ps(all, m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_permute_ps(all, m, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm512_cvtss_f32(m);
}
/// Lanes chosen by comparisons, in the form the instruction set combines and blends fastest
/// (AVX-512: a mask register; AVX2: lanes of all ones), for the packet's entry, which combines
/// many comparisons before it needs their bits.
struct Mask {
    __mmask16 k;
};
template <int P>
inline Mask where(Lanes a, Lanes b) { return {_mm512_cmp_ps_mask(a.v, b.v, P)}; }
inline Mask operator&(Mask a, Mask b) { return {__mmask16(a.k & b.k)}; }
inline Mask operator|(Mask a, Mask b) { return {__mmask16(a.k | b.k)}; }
/// The lanes of b that are not in a.
inline Mask andNot(Mask a, Mask b) { return {__mmask16(~a.k & b.k)}; }
inline Mask maskOf(unsigned bits) { return {__mmask16(bits)}; }
inline unsigned bitsOf(Mask m) { return m.k; }
inline Lanes select(Mask m, Lanes a, Lanes b) { return {_mm512_mask_mov_ps(b.v, m.k, a.v)}; }
#else
inline Lanes sub(Lanes a, Lanes b) { return {_mm256_sub_ps(a.lo, b.lo), _mm256_sub_ps(a.hi, b.hi)}; }
inline Lanes mul(Lanes a, Lanes b) { return {_mm256_mul_ps(a.lo, b.lo), _mm256_mul_ps(a.hi, b.hi)}; }
inline Lanes div(Lanes a, Lanes b) { return {_mm256_div_ps(a.lo, b.lo), _mm256_div_ps(a.hi, b.hi)}; }
inline unsigned signBits(Lanes a) {
    return unsigned(_mm256_movemask_ps(a.lo)) | unsigned(_mm256_movemask_ps(a.hi)) << 8;
}
inline Lanes add(Lanes a, Lanes b) { return {_mm256_add_ps(a.lo, b.lo), _mm256_add_ps(a.hi, b.hi)}; }
inline Lanes abs(Lanes a) {
    const __m256 m = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    return {_mm256_and_ps(a.lo, m), _mm256_and_ps(a.hi, m)};
}
inline Lanes negate(Lanes a) {
    const __m256 m = _mm256_castsi256_ps(_mm256_set1_epi32(int(0x80000000u)));
    return {_mm256_xor_ps(a.lo, m), _mm256_xor_ps(a.hi, m)};
}
template <int P>
inline unsigned compare(Lanes a, Lanes b) {
    return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(a.lo, b.lo, P))) |
           unsigned(_mm256_movemask_ps(_mm256_cmp_ps(a.hi, b.hi, P))) << 8;
}
inline Lanes mulUnfused(Lanes a, Lanes b) {
    // The barrier of unfused() (FloatBits.h) on both halves in one statement.
    __m256 lo = _mm256_mul_ps(a.lo, b.lo), hi = _mm256_mul_ps(a.hi, b.hi);
    __asm__("" : "+x"(lo), "+x"(hi));
    return {lo, hi};
}
inline Lanes max(Lanes a, Lanes b) { return {_mm256_max_ps(a.lo, b.lo), _mm256_max_ps(a.hi, b.hi)}; }
inline Lanes min(Lanes a, Lanes b) { return {_mm256_min_ps(a.lo, b.lo), _mm256_min_ps(a.hi, b.hi)}; }
inline unsigned lessEqual(Lanes a, Lanes b) {
    return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(a.lo, b.lo, _CMP_LE_OQ))) |
           unsigned(_mm256_movemask_ps(_mm256_cmp_ps(a.hi, b.hi, _CMP_LE_OQ))) << 8;
}
inline __m256 laneMask(unsigned bits) {
    const __m256i lane = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(bits)), lane), lane));
}
inline Lanes select(unsigned bits, Lanes a, Lanes b) {
    return {_mm256_blendv_ps(b.lo, a.lo, laneMask(bits & 0xffu)), _mm256_blendv_ps(b.hi, a.hi, laneMask(bits >> 8))};
}
inline Lanes Lanes::loadSome(unsigned bits, const float *p) {
    // vmaskmovps reads nothing in the lanes it leaves out (bits ≤ 8 set: the second half is empty).
    const __m256i lo = _mm256_castps_si256(laneMask(bits & 0xffu)), hi = _mm256_castps_si256(laneMask(bits >> 8));
    return {_mm256_maskload_ps(p, lo), bits >> 8 ? _mm256_maskload_ps(p + 8, hi) : _mm256_setzero_ps()};
}
inline Lanes keep(unsigned bits, Lanes a) {
    const __m256 nan = _mm256_set1_ps(std::numeric_limits<float>::quiet_NaN());
    return {_mm256_blendv_ps(nan, a.lo, laneMask(bits & 0xffu)), _mm256_blendv_ps(nan, a.hi, laneMask(bits >> 8))};
}
inline float minimum(unsigned bits, Lanes a) {
    const __m256 inf = _mm256_set1_ps(kInfinity);
    __m256 m = _mm256_min_ps(_mm256_blendv_ps(inf, a.lo, laneMask(bits & 0xffu)),
                             _mm256_blendv_ps(inf, a.hi, laneMask(bits >> 8)));
    __m128 h = _mm_min_ps(_mm256_castps256_ps128(m), _mm256_extractf128_ps(m, 1));
    h = _mm_min_ps(h, _mm_movehl_ps(h, h));
    h = _mm_min_ss(h, _mm_shuffle_ps(h, h, 1));
    return _mm_cvtss_f32(h);
}
struct Mask {
    __m256 lo, hi;
};
template <int P>
inline Mask where(Lanes a, Lanes b) { return {_mm256_cmp_ps(a.lo, b.lo, P), _mm256_cmp_ps(a.hi, b.hi, P)}; }
inline Mask operator&(Mask a, Mask b) { return {_mm256_and_ps(a.lo, b.lo), _mm256_and_ps(a.hi, b.hi)}; }
inline Mask operator|(Mask a, Mask b) { return {_mm256_or_ps(a.lo, b.lo), _mm256_or_ps(a.hi, b.hi)}; }
inline Mask andNot(Mask a, Mask b) { return {_mm256_andnot_ps(a.lo, b.lo), _mm256_andnot_ps(a.hi, b.hi)}; }
inline Mask maskOf(unsigned bits) { return {laneMask(bits & 0xffu), laneMask(bits >> 8)}; }
inline unsigned bitsOf(Mask m) {
    return unsigned(_mm256_movemask_ps(m.lo)) | unsigned(_mm256_movemask_ps(m.hi)) << 8;
}
inline Lanes select(Mask m, Lanes a, Lanes b) {
    return {_mm256_blendv_ps(b.lo, a.lo, m.lo), _mm256_blendv_ps(b.hi, a.hi, m.hi)};
}
#endif

/// The per-ray constants of the node test, in ray lanes of L (Lanes, or an AVX2 Half).
template <class L>
struct BoxRays {
    L ox, oy, oz; ///< origin
    L ix, iy, iz; ///< RayContext::invDir
    L fx, fy, fz; ///< RayContext::invDirFar
    L tLow;       ///< RayContext::tLow
};
using PacketConstants = BoxRays<Lanes>;

#if !MVCL_PACKET_AVX512
/// Eight rays, one half of Lanes: AVX2 node tests where every active ray of the packet lies in
/// one half skip the other (two thirds of a fine mesh's node tests, where the packet has split up).
struct Half {
    __m256 v;
    static Half all(float x) { return {_mm256_set1_ps(x)}; }
};
inline Half sub(Half a, Half b) { return {_mm256_sub_ps(a.v, b.v)}; }
inline Half mul(Half a, Half b) { return {_mm256_mul_ps(a.v, b.v)}; }
inline Half max(Half a, Half b) { return {_mm256_max_ps(a.v, b.v)}; }
inline Half min(Half a, Half b) { return {_mm256_min_ps(a.v, b.v)}; }
inline unsigned lessEqual(Half a, Half b) { return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ))); }
/// Smallest lane of `bits` (not empty).
inline float minimum(unsigned bits, Half a) {
    const __m256 m = _mm256_blendv_ps(_mm256_set1_ps(kInfinity), a.v, laneMask(bits));
    __m128 h = _mm_min_ps(_mm256_castps256_ps128(m), _mm256_extractf128_ps(m, 1));
    h = _mm_min_ps(h, _mm_movehl_ps(h, h));
    h = _mm_min_ss(h, _mm_shuffle_ps(h, h, 1));
    return _mm_cvtss_f32(h);
}
/// Half `which` (0: rays 0–7, 1: rays 8–15) of the node test's constants.
inline BoxRays<Half> half(const PacketConstants &k, int which) {
    auto pick = [which](const Lanes &l) { return Half{which ? l.hi : l.lo}; };
    return {pick(k.ox), pick(k.oy), pick(k.oz), pick(k.ix), pick(k.iy),
            pick(k.iz), pick(k.fx), pick(k.fy), pick(k.fz), pick(k.tLow)};
}
#endif

/// intersectBox() of child `lane` of `n` against the rays in the lanes of L, each lane with its
/// ray's operands in the same order: the entry distance of every lane in `tn`, and the bits of
/// the lanes that enter.
template <class L>
inline unsigned childAcrossRays(const WideNode &n, int lane, const int near[3], const int far[3], const BoxRays<L> &r,
                                const L &tHigh, L &tn) {
    const L tx0 = mul(sub(L::all(n.bounds[near[0]][lane]), r.ox), r.ix);
    const L ty0 = mul(sub(L::all(n.bounds[near[1]][lane]), r.oy), r.iy);
    const L tz0 = mul(sub(L::all(n.bounds[near[2]][lane]), r.oz), r.iz);
    const L tx1 = mul(sub(L::all(n.bounds[far[0]][lane]), r.ox), r.fx);
    const L ty1 = mul(sub(L::all(n.bounds[far[1]][lane]), r.oy), r.fy);
    const L tz1 = mul(sub(L::all(n.bounds[far[2]][lane]), r.oz), r.fz);
    tn = max(tx0, r.tLow);
    tn = max(ty0, tn);
    tn = max(tz0, tn);
    L tf = min(tx1, tHigh);
    tf = min(ty1, tf);
    tf = min(tz1, tf);
    return lessEqual(tn, tf);
}

/// The watertight test's per-ray constants (WatertightRay) in ray lanes, for the rays whose
/// direction has its largest component on axis kz.
struct Shear {
    int kx = 0, ky = 0, kz = 0;
    Lanes ox, oy, oz; ///< origin, permuted like the rays
    Lanes sx, sy, sz;
};

/// WatertightRay's constants of the rays with dominant axis kz: the same divisions, lane by lane.
inline Shear makeShear(const PacketRays &p, int kz) {
    Shear h;
    h.kz = kz;
    h.kx = kz + 1 == 3 ? 0 : kz + 1;
    h.ky = h.kx + 1 == 3 ? 0 : h.kx + 1;
    const float *o[3] = {p.ox, p.oy, p.oz};
    const float *d[3] = {p.dx, p.dy, p.dz};
    h.ox = Lanes::load(o[h.kx]), h.oy = Lanes::load(o[h.ky]), h.oz = Lanes::load(o[h.kz]);
    const Lanes dz = Lanes::load(d[h.kz]);
    h.sx = div(negate(Lanes::load(d[h.kx])), dz);
    h.sy = div(negate(Lanes::load(d[h.ky])), dz);
    h.sz = div(Lanes::all(1.f), dz);
    return h;
}

/// watertightIntersect4() turned around: triangle `lane` of `b` against the rays of `rays` (ray
/// lanes instead of triangle lanes), the same IEEE operations per (ray, triangle) in the same order.
/// Returns the rays hit (t, b1, b2 stored for them, each within its tCap); the rays with a zero
/// edge function are left out and returned in `onEdge`, for the scalar test and its double
/// fallback.
template <bool Barycentrics, bool OrderingError>
inline unsigned intersectAcrossRays(const Shear &r, const PrimBlock &b, int lane, unsigned rays,
                                    const Lanes &tCap, float *tOut, float *b1Out, float *b2Out, float *tErrorOut,
                                    unsigned &onEdge) {
    const Lanes zero = Lanes::all(0.f);
    const Lanes p0z = sub(Lanes::all(b.v[0][r.kz][lane]), r.oz);
    const Lanes p1z = sub(Lanes::all(b.v[1][r.kz][lane]), r.oz);
    const Lanes p2z = sub(Lanes::all(b.v[2][r.kz][lane]), r.oz);
    const Lanes p0x = add(sub(Lanes::all(b.v[0][r.kx][lane]), r.ox), mulUnfused(r.sx, p0z));
    const Lanes p0y = add(sub(Lanes::all(b.v[0][r.ky][lane]), r.oy), mulUnfused(r.sy, p0z));
    const Lanes p1x = add(sub(Lanes::all(b.v[1][r.kx][lane]), r.ox), mulUnfused(r.sx, p1z));
    const Lanes p1y = add(sub(Lanes::all(b.v[1][r.ky][lane]), r.oy), mulUnfused(r.sy, p1z));
    const Lanes p2x = add(sub(Lanes::all(b.v[2][r.kx][lane]), r.ox), mulUnfused(r.sx, p2z));
    const Lanes p2y = add(sub(Lanes::all(b.v[2][r.ky][lane]), r.oy), mulUnfused(r.sy, p2z));
    const Lanes e0 = sub(mulUnfused(p1x, p2y), mulUnfused(p1y, p2x));
    const Lanes e1 = sub(mulUnfused(p2x, p0y), mulUnfused(p2y, p0x));
    const Lanes e2 = sub(mulUnfused(p0x, p1y), mulUnfused(p0y, p1x));
    onEdge = (compare<_CMP_EQ_OQ>(e0, zero) | compare<_CMP_EQ_OQ>(e1, zero) | compare<_CMP_EQ_OQ>(e2, zero)) & rays;
    const unsigned anyNeg = compare<_CMP_LT_OQ>(e0, zero) | compare<_CMP_LT_OQ>(e1, zero) | compare<_CMP_LT_OQ>(e2, zero);
    const unsigned anyPos = compare<_CMP_GT_OQ>(e0, zero) | compare<_CMP_GT_OQ>(e1, zero) | compare<_CMP_GT_OQ>(e2, zero);
    const Lanes det = add(add(e0, e1), e2);
    unsigned candidates = rays & ~onEdge & ~(anyNeg & anyPos) & ~compare<_CMP_EQ_OQ>(det, zero);
    if (!candidates) return 0;
    const Lanes z0 = mulUnfused(r.sz, p0z), z1 = mulUnfused(r.sz, p1z), z2 = mulUnfused(r.sz, p2z);
    const Lanes tScaled = add(add(mulUnfused(e0, z0), mulUnfused(e1, z1)), mulUnfused(e2, z2));
    const Lanes bound = mulUnfused(mul(tCap, Lanes::all(kEarlyRejectSlack)), det);
    const unsigned detNeg = compare<_CMP_LT_OQ>(det, zero), detPos = compare<_CMP_GT_OQ>(det, zero);
    candidates &= ~((detNeg & (compare<_CMP_GE_OQ>(tScaled, zero) | compare<_CMP_LT_OQ>(tScaled, bound))) |
                    (detPos & (compare<_CMP_LE_OQ>(tScaled, zero) | compare<_CMP_GT_OQ>(tScaled, bound))));
    if (!candidates) return 0;
    const Lanes invDet = div(Lanes::all(1.f), det);
    const Lanes t = mulUnfused(tScaled, invDet);
    // Conservative t > δt, term by term as in watertightIntersect4().
    const Lanes maxZt = max(max(abs(z0), abs(z1)), abs(z2));
    const Lanes deltaZ = mulUnfused(Lanes::all(gamma(3)), maxZt);
    const Lanes maxXt = max(max(abs(p0x), abs(p1x)), abs(p2x));
    const Lanes maxYt = max(max(abs(p0y), abs(p1y)), abs(p2y));
    const Lanes maxPz = max(max(abs(p0z), abs(p1z)), abs(p2z));
    const Lanes deltaX = mulUnfused(Lanes::all(gamma(5)), add(maxXt, mulUnfused(abs(r.sx), maxPz)));
    const Lanes deltaY = mulUnfused(Lanes::all(gamma(5)), add(maxYt, mulUnfused(abs(r.sy), maxPz)));
    const Lanes deltaE = mulUnfused(
        Lanes::all(2.f), add(add(mulUnfused(mulUnfused(Lanes::all(gamma(2)), maxXt), maxYt), mulUnfused(deltaY, maxXt)),
                             mulUnfused(deltaX, maxYt)));
    const Lanes maxE = max(max(abs(e0), abs(e1)), abs(e2));
    const Lanes deltaT = mulUnfused(
        mulUnfused(Lanes::all(3.f), add(add(mulUnfused(mulUnfused(Lanes::all(gamma(3)), maxE), maxZt),
                                            mulUnfused(deltaE, maxZt)),
                                        mulUnfused(deltaZ, maxE))),
        abs(invDet));
    const unsigned hits = candidates & compare<_CMP_GT_OQ>(t, zero) & compare<_CMP_NLE_UQ>(t, deltaT);
    if (hits) {
        t.store(tOut);
        if (OrderingError) {
            // orderingError() lane by lane, as watertightIntersect4() computes it.
            const Lanes spread = add(add(abs(sub(z0, t)), abs(sub(z1, t))), abs(sub(z2, t)));
            const Lanes g3 = Lanes::all(gamma(3));
            const Lanes terms = add(add(mulUnfused(g3, mul(Lanes::all(2.f), maxZt)), mulUnfused(g3, abs(t))),
                                    mulUnfused(mulUnfused(deltaE, spread), abs(invDet)));
            mul(Lanes::all(2.f), terms).store(tErrorOut);
        }
        if (Barycentrics) {
            mul(e1, invDet).store(b1Out);
            mul(e2, invDet).store(b2Out);
        }
    }
    return hits;
}

/// At most this many rays reaching a leaf test it one ray at a time, four triangles per test
/// with the single-ray kernel (watertightIntersect4), instead of each triangle against all 16
/// lanes: on fine meshes a leaf is reached by one or two rays of the packet on average. A
/// triangle across the rays costs about two 16-lane tests' worth of a block test in AVX2 (two
/// halves), one in AVX-512.
inline constexpr int kRayByRayLeafRays = MVCL_PACKET_AVX512 ? 2 : 4;

/// testLeaf() for every ray of `active` (leaves without spheres): triangle by triangle across the
/// rays (intersectAcrossRays), or ray by ray four triangles at a time where few rays reach the
/// leaf, with the error bound where the closest-hit state uses it (layer priority). Either way
/// each ray meets the leaf's triangles in the same order with the single-ray arithmetic: the same
/// candidates with the same t, barycentrics and bounds, so the same results.
/// Returns the rays whose result changed (closest hit) or that are occluded (any hit), with
/// p.tCap and p.tHigh updated for them.
template <bool AnyHit, class Bests>
unsigned testLeafRays(uint32_t leaf, unsigned active, const PrimBlock *blocks, const PrimInfo *info,
                      const Shear *shears, unsigned shearLanes[3], PacketSetup &s, Bests &best) {
    PacketRays &p = s.p;
    const uint32_t first = WideLeaf::firstBlock(leaf), last = first + WideLeaf::blockCount(leaf);
    const uint32_t layerMask = s.query->layerMask;
    constexpr bool kUsesTError = !AnyHit && std::remove_reference_t<decltype(best[0])>::kUsesTError;
    unsigned changed = 0;
    unsigned open = active; ///< any hit: the rays not yet occluded
    // A hit of ray i on triangle `lane` of block bi at (t, u, v): the query's range and clips, then
    // the closest-hit state.
    auto take = [&](int i, uint32_t bi, int lane, float ti, float u, float v, float tErr) {
        const PacketLane c{s, i};
        if (!c.acceptsT(ti)) return;
        const PrimInfo &triangle = info[4 * bi + unsigned(lane)];
        if (AnyHit) {
            if (!c.acceptsPoint(ti, triangle.layer)) return;
            changed |= 1u << i;
            open &= ~(1u << i);
            p.tHigh[i] = -kInfinity;
            return;
        }
        if (!best[i].offer(c, triangleCandidate(triangle, ti, u, v), tErr)) return;
        changed |= 1u << i;
        p.tCap[i] = std::min(s.tMax[i], best[i].cap());
        p.tHigh[i] = p.tCap[i] * kTraversalSlackUp;
    };
    if (std::popcount(active) <= kRayByRayLeafRays) {
        for (unsigned rest = active; rest; rest &= rest - 1) {
            const int i = std::countr_zero(rest);
            const WatertightRay4 &ray = s.watertight(i);
            for (uint32_t bi = first; bi < last; ++bi) {
                const PrimBlock &block = blocks[bi];
                const int lanes = triangleLanes(block, layerMask);
                if (!lanes) continue;
                TriangleHit4 th;
                for (int hits = watertightIntersect4<!AnyHit, kUsesTError>(ray, block, lanes, p.tCap[i], th); hits;
                     hits &= hits - 1) {
                    const int lane = std::countr_zero(unsigned(hits));
                    take(i, bi, lane, th.t[lane], th.b1[lane], th.b2[lane], kUsesTError ? th.tError[lane] : 0.f);
                    if (AnyHit && !((open >> i) & 1u)) break;
                }
                if (AnyHit && !((open >> i) & 1u)) break;
            }
        }
        return changed;
    }
    alignas(64) float t[kPacketLanes], b1[kPacketLanes], b2[kPacketLanes], tError[kPacketLanes];
    for (int kz = 0; kz < 3; ++kz) {
        unsigned rays = active & shearLanes[kz];
        if (!rays) continue;
        const Shear &shear = shears[kz];
        for (uint32_t bi = first; bi < last; ++bi) {
            const PrimBlock &block = blocks[bi];
            for (unsigned lanes = unsigned(triangleLanes(block, layerMask)); lanes; lanes &= lanes - 1) {
                const int lane = std::countr_zero(lanes);
                unsigned onEdge = 0;
                unsigned hits = intersectAcrossRays<!AnyHit, kUsesTError>(shear, block, lane, rays, Lanes::load(p.tCap), t,
                                                                         b1, b2, tError, onEdge);
                for (; hits; hits &= hits - 1) {
                    const int i = std::countr_zero(hits);
                    take(i, bi, lane, t[i], b1[i], b2[i], kUsesTError ? tError[i] : 0.f);
                }
                for (; onEdge; onEdge &= onEdge - 1) {
                    const int i = std::countr_zero(onEdge);
                    TriangleHit h;
                    if (watertightIntersect(s.watertight(i).ray, block.vertex(lane, 0), block.vertex(lane, 1),
                                            block.vertex(lane, 2), p.tCap[i], h))
                        take(i, bi, lane, h.t, h.b1, h.b2, kUsesTError ? h.tError : 0.f);
                }
                if (AnyHit && !(rays &= open)) break;
            }
            if (AnyHit && !rays) break;
        }
    }
    return changed;
}

/// Bit i: child i of `n` holds something in the query's layers (empty children hold nothing).
/// The eight masks in one AVX2 test (both units have AVX2) instead of a branch per child.
inline unsigned childrenInLayers(const WideNode &n, uint32_t layerMask) {
    const __m256i masks = _mm256_load_si256(reinterpret_cast<const __m256i *>(n.layerMask));
    const __m256i none = _mm256_cmpeq_epi32(_mm256_and_si256(masks, _mm256_set1_epi32(int(layerMask))),
                                            _mm256_setzero_si256());
    return ~unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(none))) & 0xffu;
}

/// The walk of the rays of `lanes`, which all entered the root box and share the slab order
/// `near`/`far`: closest hit (AnyHit = false: offers candidates to best[i], ray i's NearestHit or
/// LayerPriorityHit, and returns the bits of the rays whose result changed) or any hit (returns
/// the bits of the rays that hit something). s.p.tHigh holds each ray's box culling bound and is
/// kept up to date. Flattened: the leaf test and the triangle kernel are inlined here, in this
/// instruction set, instead of being called.
template <bool AnyHit, class Bests>
__attribute__((flatten)) unsigned walk(const WideBvh &wide, unsigned lanes, const int near[3],
                                       const int far[3], const PacketConstants &k, const Shear *shears,
                                       unsigned shearLanes[3], PacketSetup &s, Bests &best) {
    PacketRays &p = s.p;
    const uint32_t layerMask = s.query->layerMask;
    const WideNode *nodes = wide.nodes.get();
    const PrimBlock *blocks = wide.blocks.get();
    const PrimInfo *info = wide.info.get();
    Lanes tHigh = Lanes::load(p.tHigh);

    // A node pushes at most kWidth − 1 children (the nearest goes straight on): the bound of the
    // single-ray stack (kStackSize) holds.
    alignas(64) float stackT[kStackSize][kPacketLanes];
    uint32_t stackRef[kStackSize];
    int sp = 0;
    uint32_t cur = wide.root;
    unsigned active = lanes;
    unsigned result = 0;
    for (;;) {
        if (WideLeaf::isLeaf(cur)) {
            bool changed = false;
            if (!WideLeaf::hasSpheres(cur)) {
                const unsigned bits = testLeafRays<AnyHit>(cur, active, blocks, info, shears, shearLanes, s, best);
                result |= bits;
                changed = bits != 0;
            } else
            for (unsigned rest = active; rest; rest &= rest - 1) {
                const int i = std::countr_zero(rest);
                const RayContext &c = s.context(i);
                if (!testLeaf<AnyHit>(cur, blocks, info, c, s.watertight(i), best[i])) continue;
                result |= 1u << i;
                changed = true;
                // An occluded ray is done: −∞ keeps it out of every box from now on.
                p.tCap[i] = AnyHit ? c.tMax : std::min(c.tMax, best[i].cap());
                p.tHigh[i] = AnyHit ? -kInfinity : p.tCap[i] * kTraversalSlackUp;
            }
            if (changed) {
                if (AnyHit && result == lanes) return result;
                tHigh = Lanes::load(p.tHigh);
            }
        } else {
            const WideNode &n = nodes[cur];
            Lanes tNear[kWidth];
            unsigned hit[kWidth];
            float key[kWidth];
            int order[kWidth];
            int count = 0;
            // The children against the rays in lanes of L (`shift`: where its first lane sits in
            // the packet); `widen` makes packet lanes of its entry distances.
            auto testChildren = [&](const auto &rays, const auto &tHighLanes, int shift, auto widen) {
                for (unsigned children = childrenInLayers(n, layerMask); children; children &= children - 1) {
                    const int lane = std::countr_zero(children);
                    std::remove_cvref_t<decltype(tHighLanes)> tn;
                    const unsigned bits = (childAcrossRays(n, lane, near, far, rays, tHighLanes, tn) << shift) & active;
                    if (!bits) continue;
                    tNear[lane] = widen(tn);
                    hit[lane] = bits;
                    // Nearest-first by the packet's nearest entry (any order gives the same hits).
                    key[lane] = AnyHit ? 0.f : minimum(bits >> shift, tn);
                    int j = count++;
                    while (j > 0 && key[order[j - 1]] < key[lane]) {
                        order[j] = order[j - 1];
                        --j;
                    }
                    order[j] = lane;
                }
            };
            auto same = [](const Lanes &t) { return t; };
#if MVCL_PACKET_AVX512
            testChildren(k, tHigh, 0, same);
#else
            // The lanes of the other half only ever meet keep() and minimum(), which leave out
            // the lanes without a bit.
            auto both = [](const Half &t) { return Lanes{t.v, t.v}; };
            if (!(active >> 8)) testChildren(half(k, 0), Half{tHigh.lo}, 0, both);
            else if (!(active & 0xffu)) testChildren(half(k, 1), Half{tHigh.hi}, 8, both);
            else testChildren(k, tHigh, 0, same);
#endif
            if (count) {
                // order[] runs from the farthest to the nearest: the nearest goes straight on.
                for (int j = 0; j + 1 < count; ++j) {
                    const int lane = order[j];
                    keep(hit[lane], tNear[lane]).store(stackT[sp]);
                    stackRef[sp++] = n.child[lane];
                }
                const int lane = order[count - 1];
                cur = n.child[lane];
                active = hit[lane];
                continue;
            }
        }
        // Pop the nearest pending subtree that some ray still needs.
        for (;;) {
            if (sp == 0) return result;
            --sp;
            active = lessEqual(Lanes::load(stackT[sp]), tHigh) & lanes;
            if (active) {
                cur = stackRef[sp];
                break;
            }
        }
    }
}

/// Rays [first, first + 8) of the `count` at `rays` as six columns of eight lanes, col[k] = the
/// k-th float of Ray (origin x, y, z, direction x, y, z); lanes at or past `count` are zero. A
/// Ray is eight floats (its cone's two last), so this is an 8 × 8 transpose of one load per ray,
/// 22 shuffles instead of 48 scalar loads and stores. AVX2, which both units have.
inline void rayColumns(const Ray *rays, int first, int count, __m256 col[6]) {
    static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, direction) == 3 * sizeof(float),
                  "a ray is one row of eight floats, origin and direction first");
    __m256 r[8];
    for (int j = 0; j < 8; ++j)
        r[j] = first + j < count ? _mm256_loadu_ps(reinterpret_cast<const float *>(rays + first + j))
                                 : _mm256_setzero_ps();
    // Pairs of rows interleaved, then quarters: u[k] holds columns k (low half) and k + 4 (high
    // half) of rows 0–3, v[k] the same of rows 4–7.
    __m256 u[4], v[4];
    for (int half = 0; half < 2; ++half) {
        const __m256 *row = r + 4 * half;
        const __m256 t0 = _mm256_unpacklo_ps(row[0], row[1]), t1 = _mm256_unpackhi_ps(row[0], row[1]);
        const __m256 t2 = _mm256_unpacklo_ps(row[2], row[3]), t3 = _mm256_unpackhi_ps(row[2], row[3]);
        __m256 *out = half ? v : u;
        out[0] = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
        out[1] = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
        out[2] = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
        out[3] = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
    }
    col[0] = _mm256_permute2f128_ps(u[0], v[0], 0x20);
    col[1] = _mm256_permute2f128_ps(u[1], v[1], 0x20);
    col[2] = _mm256_permute2f128_ps(u[2], v[2], 0x20);
    col[3] = _mm256_permute2f128_ps(u[3], v[3], 0x20);
    col[4] = _mm256_permute2f128_ps(u[0], v[0], 0x31);
    col[5] = _mm256_permute2f128_ps(u[1], v[1], 0x31);
}

/// PacketKernels::load: PacketSetup's lanes for the `count` rays of s.rays, all at once. A lane
/// is valid as isValidQuery() says (its tests on lanes: x − x = 0 for finite x, a non-zero
/// direction component, tMin ≤ tMax ordered, tMax > 0), and its dominant axis is WatertightRay's
/// choice, ties to the lower axis; lanes without a valid ray get the origin 0 and direction 1.
inline void loadPacket(PacketSetup &s, std::size_t count, const float *rayTMax) {
    const int n = int(count);
    const RayQuery &q = *s.query;
    __m256 lo[6], hi[6];
    rayColumns(s.rays, 0, n, lo);
    rayColumns(s.rays, 8, n, hi);
    Lanes col[6];
    for (int k = 0; k < 6; ++k) col[k] = Lanes::join(lo[k], hi[k]);
    const unsigned inPacketBits = (1u << n) - 1u;
    const Mask inPacket = maskOf(inPacketBits);
    // min(rayTMax[i], q.tMax) is std::min(q.tMax, rayTMax[i]) (vminps returns its second operand
    // unless the first is smaller).
    Lanes tMax = Lanes::all(q.tMax);
    if (rayTMax) tMax = select(inPacket, min(Lanes::loadSome(inPacketBits, rayTMax), tMax), tMax);
    tMax.store(s.tMax);
    const Lanes zero = Lanes::all(0.f), one = Lanes::all(1.f);
    Mask valid = inPacket;
    for (int k = 0; k < 6; ++k) valid = valid & where<_CMP_EQ_OQ>(sub(col[k], col[k]), zero);
    valid = valid & (where<_CMP_NEQ_UQ>(col[3], zero) | where<_CMP_NEQ_UQ>(col[4], zero) |
                     where<_CMP_NEQ_UQ>(col[5], zero));
    valid = valid & where<_CMP_LE_OQ>(Lanes::all(q.tMin), tMax) & where<_CMP_GT_OQ>(tMax, zero);
    PacketRays &p = s.p;
    select(valid, col[0], zero).store(p.ox);
    select(valid, col[1], zero).store(p.oy);
    select(valid, col[2], zero).store(p.oz);
    const Lanes dx = select(valid, col[3], one), dy = select(valid, col[4], one), dz = select(valid, col[5], one);
    dx.store(p.dx);
    dy.store(p.dy);
    dz.store(p.dz);
    const Lanes ax = abs(dx), ay = abs(dy), az = abs(dz);
    const Mask xMajor = where<_CMP_GE_OQ>(ax, ay) & where<_CMP_GE_OQ>(ax, az);
    const Mask yMajor = andNot(xMajor, where<_CMP_GE_OQ>(ay, az));
    s.dominantAxisLanes[0] = bitsOf(valid & xMajor);
    s.dominantAxisLanes[1] = bitsOf(valid & yMajor);
    s.dominantAxisLanes[2] = bitsOf(andNot(xMajor | yMajor, valid));
    s.valid = bitsOf(valid);
}

/// The packet query over the rays of `lanes` (s.valid or part of it): the slab constants of
/// every ray at once (the same IEEE operations as RayContext's, so the same values), the root box
/// test (intersectBox lane by lane), then one walk per direction octant. Returns as walk().
template <bool AnyHit, class Bests>
unsigned tracePacket(const WideBvh &wide, unsigned lanes, PacketSetup &s, Bests &best) {
    const RayQuery &q = *s.query;
    if (wide.blockCount == 0 || !(wide.rootMask & q.layerMask) || !lanes) return 0;
    PacketRays &p = s.p;
    PacketConstants k;
    k.ox = Lanes::load(p.ox), k.oy = Lanes::load(p.oy), k.oz = Lanes::load(p.oz);
    const Lanes one = Lanes::all(1.f), farScale = Lanes::all(kBoxFarScale);
    k.ix = div(one, Lanes::load(p.dx)), k.iy = div(one, Lanes::load(p.dy)), k.iz = div(one, Lanes::load(p.dz));
    k.fx = mul(k.ix, farScale), k.fy = mul(k.iy, farScale), k.fz = mul(k.iz, farScale);
    k.tLow = Lanes::all(q.tMin > 0.f ? q.tMin * kTraversalSlackDown : 0.f);
    // Each ray's bounds, as its single-ray query would start them (s.tMax: the query's, or the
    // ray's own range of a per-ray anyHits()).
    for (int i = 0; i < kPacketLanes; ++i) {
        p.tCap[i] = s.tMax[i];
        p.tHigh[i] = s.tMax[i] * kTraversalSlackUp;
    }
    // IEEE division keeps the sign of zero, so the sign of 1/d picks the slabs as in RayContext.
    const unsigned negative[3] = {signBits(k.ix), signBits(k.iy), signBits(k.iz)};
    const float *root = wide.rootBounds;
    auto slab = [&](int axis, bool nearSide) {
        const unsigned neg = negative[axis];
        return nearSide ? select(neg, Lanes::all(root[axis + 3]), Lanes::all(root[axis]))
                        : select(neg, Lanes::all(root[axis]), Lanes::all(root[axis + 3]));
    };
    Lanes tn = max(mul(sub(slab(0, true), k.ox), k.ix), k.tLow);
    tn = max(mul(sub(slab(1, true), k.oy), k.iy), tn);
    tn = max(mul(sub(slab(2, true), k.oz), k.iz), tn);
    Lanes tf = min(mul(sub(slab(0, false), k.ox), k.fx), Lanes::load(p.tHigh));
    tf = min(mul(sub(slab(1, false), k.oy), k.fy), tf);
    tf = min(mul(sub(slab(2, false), k.oz), k.fz), tf);
    const unsigned entering = lessEqual(tn, tf) & lanes;
    if (!entering) return 0;
    // The watertight constants of each dominant axis the entering rays have (usually one).
    Shear shears[3];
    unsigned shearLanes[3] = {};
    for (int axis = 0; axis < 3; ++axis) {
        shearLanes[axis] = s.dominantAxisLanes[axis] & entering;
        if (shearLanes[axis]) shears[axis] = makeShear(p, axis);
    }
    // One walk per octant the entering rays have (coherent rays have one), taken in the order of
    // their first rays: the walks share no ray, so their order changes no result.
    unsigned result = 0;
    for (unsigned rest = entering; rest;) {
        const int first = std::countr_zero(rest);
        unsigned group = rest;
        int near[3], far[3];
        for (int axis = 0; axis < 3; ++axis) {
            const bool neg = (negative[axis] >> first) & 1u;
            group &= neg ? negative[axis] : ~negative[axis];
            near[axis] = neg ? axis + 3 : axis;
            far[axis] = neg ? axis : axis + 3;
        }
        rest &= ~group;
        result |= walk<AnyHit>(wide, group, near, far, k, shears, shearLanes, s, best);
    }
    return result;
}

} // namespace MVCL_ISA_NAMESPACE
} // namespace mvcl::detail
