#pragma once
/// \file PolicyMapDiff.h
/// Which pixels of a view render differently under two policy maps: after a lens edit an
/// incremental renderer traces only those again.

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensRegion.h>
#include <mvcl/lens/PolicyMap.h>

#include <cstdint>
#include <vector>

namespace mvcl {

/// Sets changed[y · width + x] = 1 for every pixel of `area` (clipped to the maps) whose terms
/// differ between `before` and `after`: a different number of terms, a term whose policy does
/// not render like the other map's (PixelPolicy::rendersLike, so lens sets and table order do
/// not count), or a different weight. Terms are compared in order, as the renderer blends them
/// in order. Other entries are left as they are, so several areas or edits can be collected in
/// one mask; `changed` is enlarged to width × height entries (new ones 0) if it is smaller.
/// Runs on at most `threads` threads of the worker pool (0 = all cores). Throws mvcl::Error
/// when the maps differ in size.
MVCL_EXPORT void markChangedPixels(const PolicyMap &before, const PolicyMap &after, const PixelRect &area,
                       std::vector<uint8_t> &changed, int threads = 0);

} // namespace mvcl
