#pragma once
// Private: what a lens edit invalidates. The session compares the lenses it composed last
// with the current ones to bound the area that can change, and then the two policy maps pixel
// by pixel inside that area.

#include <mvcl/lens/Lens.h>
#include <mvcl/lens/PolicyMap.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace mvcl::detail {

/// One lens of a composed stack and the snapshot it was composed from.
struct LensState {
    std::shared_ptr<Lens> lens;
    std::shared_ptr<const LensSnapshot> snapshot;
};

/// Same lenses, same order, same snapshots.
bool sameLenses(const std::vector<LensState> &a, const std::vector<LensState> &b);

/// The pixels whose policy can differ between the two stacks: the old and new bounds of
/// every lens whose snapshot changed; the whole image when lenses were added, removed or
/// reordered.
PixelRect changedArea(const std::vector<LensState> &before, const std::vector<LensState> &after, int width,
                      int height);

/// Sets changed[y·width + x] to 1 for each pixel of `area` whose terms render differently in
/// `after` than in `before` (mvcl::markChangedPixels) and to 0 for the others of `area`;
/// returns how many changed. Pixels outside `area` are left as they are.
uint64_t markChangedPixels(const PolicyMap &before, const PolicyMap &after, const PixelRect &area,
                           std::vector<uint8_t> &changed, int threads);

} // namespace mvcl::detail
