#include "SessionPolicyDiff_p.h"

#include <mvcl/core/WorkerPool.h>

#include <algorithm>
#include <atomic>
#include <cstring>

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

/// Everything of a policy that changes radiance (not lensSet, which only serves costs).
/// Byte comparison: equal bytes are certainly equal policies; unequal padding at worst makes
/// a pixel re-traced that did not need it.
bool rendersLike(const PixelPolicy &a, const PixelPolicy &b) {
    return std::memcmp(&a.ray, &b.ray, sizeof(RayPolicy)) == 0 && a.sampleFromScreen == b.sampleFromScreen;
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
    // Policies are matched once per map pair, not per pixel: each policy of either map gets
    // the index of the first policy of `before` that renders like it (kNone if there is none).
    constexpr uint32_t kNone = 0xffffffffu;
    auto firstLike = [&](const PixelPolicy &p) {
        for (size_t i = 0; i < before.policies().size(); ++i)
            if (rendersLike(p, before.policies()[i])) return uint32_t(i);
        return kNone;
    };
    std::vector<uint32_t> canonicalBefore, canonicalAfter;
    for (const PixelPolicy &p : before.policies()) canonicalBefore.push_back(firstLike(p));
    for (const PixelPolicy &p : after.policies()) canonicalAfter.push_back(firstLike(p));
    const int width = after.width();
    std::atomic<uint64_t> total{0};
    parallelFor(size_t(std::max(area.y1 - area.y0, 0)), threads, [&](size_t row) {
        const int y = area.y0 + int(row);
        uint64_t count = 0;
        for (int x = area.x0; x < area.x1; ++x) {
            const std::span<const PolicyTerm> was = before.terms(x, y), is = after.terms(x, y);
            bool differs = was.size() != is.size();
            for (size_t t = 0; !differs && t < is.size(); ++t)
                differs = canonicalAfter[is[t].policy] != canonicalBefore[was[t].policy] ||
                          is[t].weight != was[t].weight;
            changed[size_t(y) * size_t(width) + size_t(x)] = differs;
            count += differs;
        }
        total += count;
    });
    return total.load();
}

} // namespace mvcl::detail
