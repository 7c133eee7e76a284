#pragma once
// Private: the closest-hit state of a query that can reach one layer only: the nearest hit in the
// total order (t, layer, kind, geometry, primitive) of hitPrecedes(). Traversal is written against
// this interface and LayerPriorityHit's, so a single-layer query runs exactly the code it ran
// before layer priority existed.

#include "KernelIsa.h"
#include "RayContext.h"

#include <mvcl/tracer/Hit.h>

namespace mvcl::detail {

class NearestHit {
public:
    /// offer() ignores the error bound, so the kernel need not compute it.
    static constexpr bool kUsesTError = false;
    /// Hits beyond this t cannot change the result (the traversal and kernel cap).
    MVCL_KERNEL_INLINE float cap() const { return m_best.t; }
    /// False when a hit at t (and every farther hit of the same primitive) cannot change the result.
    MVCL_KERNEL_INLINE bool mayMatter(const Hit &cand) const { return hitPrecedes(cand, m_best); }
    /// Offers an accepted-range candidate with the error bound of its t (unused here). Returns
    /// true if the result changed. `c` is the ray's RayContext, or a PacketLane (PacketSetup.h):
    /// anything with the clip test acceptsPoint(t, layer).
    template <class Context>
    MVCL_KERNEL_INLINE bool offer(const Context &c, const Hit &cand, float /*tError*/) {
        if (!hitPrecedes(cand, m_best)) return false;
        if (!c.acceptsPoint(cand.t, cand.layer)) return false;
        m_best = cand;
        return true;
    }
    MVCL_KERNEL_INLINE bool resolve(Hit &out) const {
        if (!m_best.isValid()) return false;
        out = m_best;
        return true;
    }

private:
    Hit m_best;
};

} // namespace mvcl::detail
