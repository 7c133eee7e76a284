// Private: packet traversal of the wide BVH, 16 rays at once (a 4×4 tile of coherent rays), included
// twice by Tracer.cpp: as namespace `packet_avx2` inside `#pragma GCC target("avx2")` (the 16 rays
// as two 8-lane halves) and as `packet_avx512` inside `#pragma GCC target("avx512f")` (one 16-lane
// register), chosen at run time. No include guard on purpose.
//
// Each child box is tested against all rays of the packet (ray lanes, not child lanes), with the
// arithmetic of intersectBox() lane by lane: same operands, same order, same NaN rule. A ray
// enters every box its own single-ray traversal could need, so the nearest hit in the total order
// of hitPrecedes() (and layer priority's window, a function of the candidate set) is found
// whatever order the packet visits the leaves in: the results are those of Tracer::closestHit()
// bit for bit. Leaves are tested ray by ray with the single-ray 4-triangle kernel (testLeaf), so
// every t and barycentric is the same arithmetic too.
//
// The packet shares one near/far slab choice: Tracer.cpp splits a packet by direction octant
// first. Expects MVCL_PACKET_NS, MVCL_PACKET_AVX512 (0 or 1) and the helpers of Tracer.cpp.

namespace MVCL_PACKET_NS {

using detail::kPacketLanes;
using detail::kWidth;
using detail::PacketRays;
using detail::RayContext;
using detail::WideLeaf;
using detail::WideNode;

/// Sixteen floats, one per ray of the packet.
struct Lanes {
#if MVCL_PACKET_AVX512
    __m512 v;
    static Lanes load(const float *p) { return {_mm512_load_ps(p)}; }
    static Lanes all(float x) { return {_mm512_set1_ps(x)}; }
    void store(float *p) const { _mm512_store_ps(p, v); }
#else
    __m256 lo, hi;
    static Lanes load(const float *p) { return {_mm256_load_ps(p), _mm256_load_ps(p + 8)}; }
    static Lanes all(float x) { return {_mm256_set1_ps(x), _mm256_set1_ps(x)}; }
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
    __m512 m = _mm512_mask_mov_ps(_mm512_set1_ps(detail::kInfinity), __mmask16(bits), a.v);
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_shuffle_f32x4(all, m, m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_shuffle_f32x4(all, m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_permute_ps(all, m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm512_maskz_min_ps(all, m, _mm512_maskz_permute_ps(all, m, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm512_cvtss_f32(m);
}
#else
inline Lanes sub(Lanes a, Lanes b) { return {_mm256_sub_ps(a.lo, b.lo), _mm256_sub_ps(a.hi, b.hi)}; }
inline Lanes mul(Lanes a, Lanes b) { return {_mm256_mul_ps(a.lo, b.lo), _mm256_mul_ps(a.hi, b.hi)}; }
inline Lanes div(Lanes a, Lanes b) { return {_mm256_div_ps(a.lo, b.lo), _mm256_div_ps(a.hi, b.hi)}; }
inline unsigned signBits(Lanes a) {
    return unsigned(_mm256_movemask_ps(a.lo)) | unsigned(_mm256_movemask_ps(a.hi)) << 8;
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
inline Lanes keep(unsigned bits, Lanes a) {
    const __m256 nan = _mm256_set1_ps(std::numeric_limits<float>::quiet_NaN());
    return {_mm256_blendv_ps(nan, a.lo, laneMask(bits & 0xffu)), _mm256_blendv_ps(nan, a.hi, laneMask(bits >> 8))};
}
inline float minimum(unsigned bits, Lanes a) {
    const __m256 inf = _mm256_set1_ps(detail::kInfinity);
    __m256 m = _mm256_min_ps(_mm256_blendv_ps(inf, a.lo, laneMask(bits & 0xffu)),
                             _mm256_blendv_ps(inf, a.hi, laneMask(bits >> 8)));
    __m128 h = _mm_min_ps(_mm256_castps256_ps128(m), _mm256_extractf128_ps(m, 1));
    h = _mm_min_ps(h, _mm_movehl_ps(h, h));
    h = _mm_min_ss(h, _mm_shuffle_ps(h, h, 1));
    return _mm_cvtss_f32(h);
}
#endif

/// The per-ray constants of the node test, in ray lanes.
struct PacketConstants {
    Lanes ox, oy, oz; ///< origin
    Lanes ix, iy, iz; ///< RayContext::invDir
    Lanes fx, fy, fz; ///< RayContext::invDirFar
    Lanes tLow;       ///< RayContext::tLow
};

/// The walk of the rays of `lanes`, which all entered the root box and share the slab order
/// `near`/`far`: closest hit (AnyHit = false: offers candidates to best[i], ray i's NearestHit or
/// LayerPriorityHit, and returns the bits of the rays whose result changed) or any hit (returns
/// the bits of the rays that hit something). s.p.tHigh holds each ray's box culling bound and is
/// kept up to date. Flattened: the leaf test and the triangle kernel are inlined here, in this
/// instruction set, instead of being called.
template <bool AnyHit, class Bests>
__attribute__((flatten)) unsigned walk(const detail::WideBvh &wide, unsigned lanes, const int near[3],
                                       const int far[3], const PacketConstants &k, PacketSetup &s, Bests &best) {
    PacketRays &p = s.p;
    const uint32_t layerMask = s.query->layerMask;
    const WideNode *nodes = wide.nodes.get();
    const detail::PrimBlock *blocks = wide.blocks.get();
    const detail::PrimInfo *info = wide.info.get();
    const Lanes ox = k.ox, oy = k.oy, oz = k.oz, ix = k.ix, iy = k.iy, iz = k.iz, fx = k.fx, fy = k.fy, fz = k.fz;
    const Lanes tLow = k.tLow;
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
            for (unsigned rest = active; rest; rest &= rest - 1) {
                const int i = std::countr_zero(rest);
                const RayContext &c = s.context(i);
                if (!testLeaf<AnyHit>(cur, blocks, info, c, *s.wray4[i], best[i])) continue;
                result |= 1u << i;
                changed = true;
                // An occluded ray is done: −∞ keeps it out of every box from now on.
                p.tHigh[i] = AnyHit ? -detail::kInfinity
                                    : std::min(c.tMax, best[i].cap()) * detail::kTraversalSlackUp;
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
            for (int lane = 0; lane < kWidth; ++lane) {
                if (!(n.layerMask[lane] & layerMask)) continue;
                const Lanes tx0 = mul(sub(Lanes::all(n.bounds[near[0]][lane]), ox), ix);
                const Lanes ty0 = mul(sub(Lanes::all(n.bounds[near[1]][lane]), oy), iy);
                const Lanes tz0 = mul(sub(Lanes::all(n.bounds[near[2]][lane]), oz), iz);
                const Lanes tx1 = mul(sub(Lanes::all(n.bounds[far[0]][lane]), ox), fx);
                const Lanes ty1 = mul(sub(Lanes::all(n.bounds[far[1]][lane]), oy), fy);
                const Lanes tz1 = mul(sub(Lanes::all(n.bounds[far[2]][lane]), oz), fz);
                Lanes tn = max(tx0, tLow);
                tn = max(ty0, tn);
                tn = max(tz0, tn);
                Lanes tf = min(tx1, tHigh);
                tf = min(ty1, tf);
                tf = min(tz1, tf);
                const unsigned bits = lessEqual(tn, tf) & active;
                if (!bits) continue;
                tNear[lane] = tn;
                hit[lane] = bits;
                // Nearest-first by the packet's nearest entry (any order gives the same hits).
                key[lane] = AnyHit ? 0.f : minimum(bits, tn);
                int j = count++;
                while (j > 0 && key[order[j - 1]] < key[lane]) {
                    order[j] = order[j - 1];
                    --j;
                }
                order[j] = lane;
            }
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

/// The packet query over the rays of `lanes` (s.valid or part of it): the slab constants of
/// every ray at once (the same IEEE operations as RayContext's, so the same values), the root box
/// test (intersectBox lane by lane), then one walk per direction octant. Returns as walk().
template <bool AnyHit, class Bests>
unsigned tracePacket(const detail::WideBvh &wide, unsigned lanes, PacketSetup &s, Bests &best) {
    const RayQuery &q = *s.query;
    if (wide.blockCount == 0 || !(wide.rootMask & q.layerMask) || !lanes) return 0;
    PacketRays &p = s.p;
    PacketConstants k;
    k.ox = Lanes::load(p.ox), k.oy = Lanes::load(p.oy), k.oz = Lanes::load(p.oz);
    const Lanes one = Lanes::all(1.f), farScale = Lanes::all(detail::kBoxFarScale);
    k.ix = div(one, Lanes::load(p.dx)), k.iy = div(one, Lanes::load(p.dy)), k.iz = div(one, Lanes::load(p.dz));
    k.fx = mul(k.ix, farScale), k.fy = mul(k.iy, farScale), k.fz = mul(k.iz, farScale);
    k.tLow = Lanes::all(q.tMin > 0.f ? q.tMin * detail::kTraversalSlackDown : 0.f);
    const float tHigh = q.tMax * detail::kTraversalSlackUp;
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
    Lanes tf = min(mul(sub(slab(0, false), k.ox), k.fx), Lanes::all(tHigh));
    tf = min(mul(sub(slab(1, false), k.oy), k.fy), tf);
    tf = min(mul(sub(slab(2, false), k.oz), k.fz), tf);
    const unsigned entering = lessEqual(tn, tf) & lanes;
    for (int i = 0; i < kPacketLanes; ++i) p.tHigh[i] = tHigh;
    unsigned result = 0;
    for (int octant = 0; octant < 8; ++octant) {
        unsigned group = entering;
        int near[3], far[3];
        for (int axis = 0; axis < 3; ++axis) {
            const bool neg = (octant >> axis) & 1;
            group &= neg ? negative[axis] : ~negative[axis];
            near[axis] = neg ? axis + 3 : axis;
            far[axis] = neg ? axis : axis + 3;
        }
        if (group) result |= walk<AnyHit>(wide, group, near, far, k, s, best);
    }
    return result;
}

} // namespace MVCL_PACKET_NS
