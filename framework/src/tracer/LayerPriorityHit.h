#pragma once
// Private: the closest-hit state of a query that can reach two or more layers. Nested layers a
// hair apart (or touching) must not z-fight: where float rounding cannot tell which surface is
// nearer, the outer layer (the lower number) wins.
//
// The rule, as a function of the set of candidates (so the answer does not depend on the BVH, the
// leaf size, the thread count or SSE/AVX2):
//   - every candidate c (in the query's layers, t range and clip volumes) has an error bound δc
//     on its t from the intersection test's error analysis (orderingError() in
//     WatertightTriangle.h; γ₂·t for the double-precision spheres and planes);
//   - the window ends at E = min over candidates of tc + max(2·δc, contact), where contact is the
//     scene's contact tolerance in units of this ray's t (0 when off). 2·δc is the combined bound
//     of two hits whose bounds are both δc: two surfaces a hair apart are hit at the same place
//     by the same ray, with t bounds of the same size;
//   - the winner is the nearest hit (t, kind, geometry, primitive) of the lowest layer that has a
//     hit with t ≤ E. The nearest hit overall always qualifies, so there is always a winner.
// E only shrinks as candidates arrive, so traversal may cull every box beyond the current E; a
// layer's nearest hit is kept per layer because a shrinking E can drop the current winner and
// hand the result to a layer seen before. Exact ties resolve as in NearestHit (lower layer), and
// when no other layer has a hit within the window the result is NearestHit's.

#include "KernelIsa.h"
#include "RayContext.h"

#include <mvcl/model/LayerTable.h>
#include <mvcl/tracer/Hit.h>

#include <algorithm>
#include <bit>
#include <cstdint>

namespace mvcl::detail {

class LayerPriorityHit {
public:
    static constexpr bool kUsesTError = true;
    /// contactWindow: the scene's contact tolerance divided by the ray direction's length.
    MVCL_KERNEL_INLINE explicit LayerPriorityHit(float contactWindow) : m_contactWindow(contactWindow) {}

    MVCL_KERNEL_INLINE float cap() const { return m_windowEnd; }
    MVCL_KERNEL_INLINE bool mayMatter(const Hit &cand) const { return cand.t <= m_windowEnd; }
    /// As NearestHit::offer().
    template <class Context>
    MVCL_KERNEL_INLINE bool offer(const Context &c, const Hit &cand, float tError) {
        if (!(cand.t <= m_windowEnd)) return false;
        const float end = cand.t + std::max(2.f * tError, m_contactWindow);
        const uint32_t bit = 1u << cand.layer;
        const bool improvesLayer = !(m_layers & bit) || hitPrecedes(cand, m_nearest[cand.layer].hit);
        const bool narrows = end < m_windowEnd;
        if (!improvesLayer && !narrows) return false;
        if (!c.acceptsPoint(cand.t, cand.layer)) return false;
        if (narrows) m_windowEnd = end;
        if (improvesLayer) {
            m_nearest[cand.layer].hit = cand;
            m_layers |= bit;
        }
        return true;
    }
    MVCL_KERNEL_INLINE bool resolve(Hit &out) const {
        for (uint32_t rest = m_layers; rest; rest &= rest - 1) {
            const Hit &h = m_nearest[std::countr_zero(rest)].hit;
            if (h.t <= m_windowEnd) {
                out = h;
                return true;
            }
        }
        return false;
    }

private:
    /// Left uninitialised: only the slots of m_layers are ever read, and a query touches one or
    /// two of the 32.
    union Slot {
        Slot() {}
        Hit hit;
    };
    float m_windowEnd = kInfinity;
    float m_contactWindow;
    uint32_t m_layers = 0;
    Slot m_nearest[kMaxLayers];
};

} // namespace mvcl::detail
