#pragma once
// Private: what a packet query hands to the packet walk of its instruction set (KernelTables.h):
// the rays in lanes with each ray's context made on demand, and the rays' closest-hit states. One
// type for every instruction set: the members the walk calls are MVCL_KERNEL_INLINE (KernelIsa.h).

#include "KernelIsa.h"
#include "NearestHit.h"
#include "PacketRays.h"
#include "RayContext.h"
#include "WatertightTriangle4.h"

#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <type_traits>

namespace mvcl::detail {

/// Storage for a T made later with placement new, left uninitialised until then: arrays of
/// std::optional are zeroed when the struct holding them is made, which cost packet queries
/// as much as their walk. Only for trivially destructible T (never destroyed).
template <class T>
union Slot {
    static_assert(std::is_trivially_destructible_v<T>);
    Slot() {}
    T value;
};

struct PacketSetup;

/// What a triangle hit of ray i needs from its query, read from the packet instead of a
/// RayContext (whose reciprocals and slab order the packet walk has in lanes already): the
/// range test and the clip test, the expressions of RayContext::acceptsT() and acceptsPoint().
struct PacketLane {
    const PacketSetup &s;
    int i;
    MVCL_KERNEL_INLINE bool acceptsT(float t) const;
    MVCL_KERNEL_INLINE bool acceptsPoint(float t, uint32_t layer) const;
};

/// A packet query's rays: their origins and directions in lanes, and each ray's context and
/// single-ray triangle-kernel constants, made only where the ray needs them: the context for a
/// leaf holding spheres and for the planes (triangle hits go through PacketLane), the kernel
/// constants for those leaves, for a leaf few rays reach and for a zero edge function (the
/// scalar fallback).
struct PacketSetup {
    const Ray *rays = nullptr;
    const RayQuery *query = nullptr;
    /// Each ray's upper bound: the query's, or min(query.tMax, tMax[i]) for anyHits() with
    /// per-ray ranges (the expression a single query with that tMax would hold). Lanes without a
    /// valid ray hold harmless constants here and in p; no walk ever reads them.
    alignas(64) float tMax[kPacketLanes];
    float tMin = 0.f;   ///< the query's
    bool hasClips = false; ///< the query has clip volumes
    unsigned valid = 0; ///< rays with a valid query
    unsigned built = 0; ///< rays whose context exists
    unsigned watertightBuilt = 0; ///< rays whose WatertightRay and WatertightRay4 exist
    unsigned dominantAxisLanes[3] = {}; ///< rays by WatertightRay::kz (the largest |direction| axis)
    PacketRays p;
    Slot<RayContext> contexts[kPacketLanes];
    Slot<WatertightRay> wrayStorage[kPacketLanes];
    Slot<WatertightRay4> wray4s[kPacketLanes];

    /// Made by Tracer (baseline code) for the rays at `r`; the packet table's load()
    /// (KernelTables.h) then fills tMax, valid, dominantAxisLanes and p, all lanes at once in its
    /// instruction set. The walks call context() and watertight().
    PacketSetup(const Ray *r, const RayQuery &q)
        : rays(r), query(&q), tMin(q.tMin), hasClips(q.clipCount() > 0) {}
    PacketSetup(const PacketSetup &) = delete;
    PacketSetup &operator=(const PacketSetup &) = delete;

    MVCL_KERNEL_INLINE const RayContext &context(int i) {
        if (!((built >> i) & 1u)) {
            new (&contexts[i].value) RayContext(rays[i], *query, tMax[i]);
            built |= 1u << i;
        }
        return contexts[i].value;
    }
    /// Ray i's constants of the single-ray triangle kernels (its WatertightRay is .ray).
    MVCL_KERNEL_INLINE const WatertightRay4 &watertight(int i) {
        if (!((watertightBuilt >> i) & 1u)) {
            new (&wray4s[i].value) WatertightRay4(*new (&wrayStorage[i].value) WatertightRay(rays[i]));
            watertightBuilt |= 1u << i;
        }
        return wray4s[i].value;
    }
};

MVCL_KERNEL_INLINE bool PacketLane::acceptsT(float t) const {
    return t > 0.f && t >= s.tMin && t <= s.tMax[i] && t < kInfinity;
}
MVCL_KERNEL_INLINE bool PacketLane::acceptsPoint(float t, uint32_t layer) const {
    return !s.hasClips || clipsAcceptAt(*s.query, s.rays[i], t, layer);
}

/// The closest-hit states of a packet's rays, made in place (LayerPriorityHit takes an argument)
/// by the caller of the walk.
template <class Best>
struct PacketBests {
    Slot<Best> slot[kPacketLanes]; ///< made for the valid rays only
    MVCL_KERNEL_INLINE Best &operator[](int i) { return slot[i].value; }
};

/// Any-hit queries need a Best only for the type: one shared, never read.
struct UnusedBests {
    NearestHit unused;
    MVCL_KERNEL_INLINE NearestHit &operator[](int) { return unused; }
};

} // namespace mvcl::detail
