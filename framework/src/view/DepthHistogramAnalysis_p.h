#pragma once
// Private: from the surface crossings of the sampled rays to the binned DepthHistogram and its
// suggestions for d. Separate from the sampling so the rules can be read (and changed) apart
// from the ray walks.

#include <mvcl/tracer/Hit.h>
#include <mvcl/view/DepthHistogram.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace mvcl {

class LayerTable;

namespace detail {

/// Which surface a crossing is on: the geometry and the side the ray meets. Two crossings with
/// equal keys on neighbouring rays lie on one continuous piece of surface (for closed convex
/// shapes exactly; for others it is a good sign).
uint64_t surfaceKey(const Hit &hit, bool frontFacing);

/// The crossings of every sampled ray, flattened: ray r owns [begin[r], begin[r + 1]), in
/// increasing t.
struct RayCrossings {
    std::vector<uint32_t> begin{0};
    std::vector<float> t;
    std::vector<uint8_t> layer;
    std::vector<uint64_t> surface; ///< surfaceKey() per crossing
    /// Per ray: the walk stopped at the cap with surfaces still behind.
    std::vector<uint8_t> truncated;
    /// Pairs of rays through neighbouring grid pixels (left-right and up-down).
    std::vector<std::pair<uint32_t, uint32_t>> neighbours;

    uint32_t rayCount() const { return uint32_t(begin.size() - 1); }
};

/// Fills the bins, per-layer entries, ray counts and suggestions of a histogram (not its
/// timing or pixel step).
DepthHistogram analyseCrossings(const RayCrossings &rays, const LayerTable &layers,
                                const DepthHistogramSettings &settings);

} // namespace detail
} // namespace mvcl
