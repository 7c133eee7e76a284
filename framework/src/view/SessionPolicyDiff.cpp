#include "SessionPolicyDiff_p.h"

#include <mvcl/lens/PolicyMapDiff.h>

#include <mvcl/core/WorkerPool.h>

#include <algorithm>
#include <atomic>

namespace mvcl::detail {

namespace {

PixelRect boundsOf(const LensState &state, int width, int height) {
    return state.snapshot ? state.snapshot->region.pixelBounds(width, height) : PixelRect{};
}

PixelRect unite(const PixelRect &a, const PixelRect &b) {
    if (a.isEmpty()) return b;
    if (b.isEmpty()) return a;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

} // namespace

bool sameLenses(const std::vector<LensState> &a, const std::vector<LensState> &b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].lens != b[i].lens || a[i].snapshot != b[i].snapshot) return false;
    return true;
}

PixelRect changedArea(const std::vector<LensState> &before, const std::vector<LensState> &after, int width,
                      int height) {
    const PixelRect all{0, 0, width, height};
    if (before.size() != after.size()) return all;
    PixelRect area;
    for (size_t i = 0; i < before.size(); ++i) {
        if (before[i].lens != after[i].lens) return all;
        if (before[i].snapshot == after[i].snapshot) continue;
        area = unite(area, unite(boundsOf(before[i], width, height), boundsOf(after[i], width, height)));
    }
    return area;
}

uint64_t markChangedPixels(const PolicyMap &before, const PolicyMap &after, const PixelRect &area,
                           std::vector<uint8_t> &changed, int threads) {
    // markChangedPixels only sets marks: the area is cleared first, as the mask is reused.
    const int width = after.width();
    changed.resize(size_t(width) * size_t(after.height()), 0);
    for (int y = std::max(area.y0, 0); y < area.y1; ++y)
        std::fill_n(changed.data() + size_t(y) * size_t(width) + size_t(area.x0), size_t(area.x1 - area.x0), uint8_t(0));
    mvcl::markChangedPixels(before, after, area, changed, threads);
    std::atomic<uint64_t> total{0};
    parallelFor(size_t(std::max(area.y1 - area.y0, 0)), threads, [&](size_t row) {
        const uint8_t *line = changed.data() + size_t(area.y0 + int(row)) * size_t(width);
        uint64_t count = 0;
        for (int x = area.x0; x < area.x1; ++x) count += line[x];
        total += count;
    });
    return total.load();
}

} // namespace mvcl::detail
