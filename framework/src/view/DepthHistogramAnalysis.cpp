#include "DepthHistogramAnalysis_p.h"

#include <mvcl/model/LayerTable.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace mvcl::detail {

namespace {

/// Hits carry uint8 layers; the tracer clamps them below kMaxLayers.
constexpr int kLayerSlots = 256;

struct BinLayout {
    double tNear = 0.0;
    double width = 1.0;
    int count = 1;

    /// Monotone in t, so the crossings of bins [a, b] are one contiguous run of the sorted t.
    int binOf(float t) const {
        const double f = std::floor((double(t) - tNear) / width);
        return int(std::clamp(f, 0.0, double(count - 1)));
    }
};

/// Midpoint of (a, b), or nullopt if no float lies strictly between them.
std::optional<float> strictMidpoint(float a, float b) {
    const float m = float(0.5 * (double(a) + double(b)));
    if (!(m > a && m < b)) return std::nullopt;
    return m;
}

int mostCommon(const std::array<uint32_t, kLayerSlots> &counts) {
    const auto best = std::max_element(counts.begin(), counts.end());
    return *best == 0 ? -1 : int(best - counts.begin());
}

/// Index (into RayCrossings::t) of ray r's first crossing at or beyond d.
uint32_t firstAtOrBeyond(const RayCrossings &rays, uint32_t r, float d) {
    const auto first = rays.t.begin() + rays.begin[r], last = rays.t.begin() + rays.begin[r + 1];
    return uint32_t(std::lower_bound(first, last, d) - rays.t.begin());
}

/// True if a surface passes through distance d between two neighbouring rays: one ray's last
/// crossing before d and the other's first crossing beyond it are on the same surface. A run of
/// empty bins there is a hole in the sampling (a surface steep in t, seen at a grazing angle),
/// not a gap between surfaces.
bool surfaceSpans(const RayCrossings &rays, float d) {
    for (const auto &[a, b] : rays.neighbours) {
        const uint32_t splitA = firstAtOrBeyond(rays, a, d), splitB = firstAtOrBeyond(rays, b, d);
        if (splitA > rays.begin[a] && splitB < rays.begin[b + 1] && rays.surface[splitA - 1] == rays.surface[splitB])
            return true;
        if (splitB > rays.begin[b] && splitA < rays.begin[a + 1] && rays.surface[splitB - 1] == rays.surface[splitA])
            return true;
    }
    return false;
}

/// Which rays a lens distance d splits: those with crossings before d and at or beyond it
/// (t ≥ tMin stays visible, so a crossing at exactly d is beyond). A truncated ray has
/// surfaces beyond its last recorded crossing.
void measureSeparation(const RayCrossings &rays, DepthSuggestion &s) {
    std::array<uint32_t, kLayerSlots> before{}, after{};
    uint32_t separated = 0;
    for (uint32_t r = 0; r < rays.rayCount(); ++r) {
        const uint32_t beyond = firstAtOrBeyond(rays, r, s.distance);
        if (beyond == rays.begin[r]) continue;
        if (beyond == rays.begin[r + 1] && !rays.truncated[r]) continue;
        ++separated;
        ++before[rays.layer[beyond - 1]];
        if (beyond < rays.begin[r + 1]) ++after[rays.layer[beyond]];
    }
    s.raysSeparated = separated;
    s.layerBefore = mostCommon(before);
    s.layerAfter = mostCommon(after);
}

/// The widest interval between consecutive sorted crossings in [first, last] (indices).
std::pair<float, float> widestInterval(const std::vector<float> &sorted, std::size_t first, std::size_t last) {
    std::pair<float, float> best{sorted[first], sorted[first]};
    for (std::size_t i = first; i < last; ++i)
        if (double(sorted[i + 1]) - double(sorted[i]) > double(best.second) - double(best.first))
            best = {sorted[i], sorted[i + 1]};
    return best;
}

/// Suggestions in runs of empty or near-empty bins between populated ones: the midpoint of the
/// widest crossing-free interval in the run, if that interval is at least a bin wide (a
/// near-empty run inside a sparse cluster has only narrow holes) and no surface spans it.
void addEmptyRunSuggestions(const DepthHistogram &h, const RayCrossings &rays, const std::vector<float> &sorted,
                            const std::vector<uint64_t> &before, double nearEmptyCount,
                            std::vector<DepthSuggestion> &out) {
    const int n = h.binCount();
    const auto populated = [&](int i) { return double(h.counts[std::size_t(i)]) > nearEmptyCount; };
    int first = 0;
    while (first < n && !populated(first)) ++first;
    int last = n - 1;
    while (last > first && !populated(last)) --last;
    for (int i = first + 1; i < last;) {
        if (populated(i)) {
            ++i;
            continue;
        }
        const int runBegin = i;
        while (!populated(i)) ++i; // stops at `last` at the latest
        // sorted[lo] is the last crossing before the run, sorted[hi] the first after it.
        const std::size_t lo = std::size_t(before[std::size_t(runBegin)] - 1);
        const std::size_t hi = std::size_t(before[std::size_t(i)]);
        const auto [gapBegin, gapEnd] = widestInterval(sorted, lo, hi);
        if (double(gapEnd) - double(gapBegin) < double(h.binWidth())) continue;
        const std::optional<float> d = strictMidpoint(gapBegin, gapEnd);
        if (!d || surfaceSpans(rays, *d)) continue;
        DepthSuggestion s;
        s.distance = *d;
        s.reason = DepthSuggestion::Reason::EmptyRun;
        s.gapBegin = gapBegin;
        s.gapEnd = gapEnd;
        out.push_back(s);
    }
}

/// One suggestion just before each layer's first crossing (in order of first crossings, all
/// but the nearest layer): between the crossing before it and that first crossing, at most a
/// bin before it. Skipped where an empty-run suggestion already covers the same interval.
void addLayerTransitionSuggestions(const DepthHistogram &h, const std::vector<float> &sorted,
                                   std::vector<DepthSuggestion> &out) {
    const std::size_t emptyRuns = out.size();
    for (const LayerDepths &layer : h.layers) {
        const auto at = std::lower_bound(sorted.begin(), sorted.end(), layer.nearest);
        if (at == sorted.begin()) continue; // the nearest layer (or tied with it)
        const float previous = *(at - 1);
        const std::optional<float> mid = strictMidpoint(previous, layer.nearest);
        if (!mid) continue;
        const float justBefore = layer.nearest - h.binWidth();
        DepthSuggestion s;
        s.distance = justBefore > *mid && justBefore < layer.nearest ? justBefore : *mid;
        s.reason = DepthSuggestion::Reason::LayerTransition;
        s.gapBegin = previous;
        s.gapEnd = layer.nearest;
        const bool covered = std::any_of(out.begin(), out.begin() + std::ptrdiff_t(emptyRuns), [&](const DepthSuggestion &e) {
            return e.gapBegin == s.gapBegin && e.gapEnd == s.gapEnd;
        });
        if (!covered) out.push_back(s);
    }
}

} // namespace

uint64_t surfaceKey(const Hit &hit, bool frontFacing) {
    return uint64_t(hit.geometry) << 3 | uint64_t(hit.kind) << 1 | uint64_t(frontFacing);
}

DepthHistogram analyseCrossings(const RayCrossings &rays, const LayerTable &layerTable,
                                const DepthHistogramSettings &settings) {
    DepthHistogram h;
    h.raysSampled = rays.rayCount();
    for (uint32_t r = 0; r < rays.rayCount(); ++r) {
        if (rays.begin[r + 1] > rays.begin[r]) ++h.raysHit;
        if (rays.truncated[r]) ++h.raysTruncated;
    }
    if (rays.t.empty()) return h;

    // The bin range: fixed by the settings, or fitted to the crossings.
    if (settings.tFar > settings.tNear) {
        h.tNear = settings.tNear;
        h.tFar = settings.tFar;
    } else {
        const auto [lo, hi] = std::minmax_element(rays.t.begin(), rays.t.end());
        h.tNear = *lo;
        h.tFar = *hi;
        if (!(h.tFar > h.tNear)) h.tFar = h.tNear + std::max(std::fabs(h.tNear), 1.f) * 1e-3f;
    }
    BinLayout bins;
    bins.count = std::max(settings.binCount, 1);
    bins.tNear = h.tNear;
    bins.width = (double(h.tFar) - double(h.tNear)) / double(bins.count);
    h.counts.assign(std::size_t(bins.count), 0);

    std::array<int, kLayerSlots> slotOfLayer;
    slotOfLayer.fill(-1);
    std::vector<LayerDepths> byFirstUse;
    std::vector<float> sorted;
    sorted.reserve(rays.t.size());
    for (uint32_t r = 0; r < rays.rayCount(); ++r) {
        for (uint32_t i = rays.begin[r]; i < rays.begin[r + 1]; ++i) {
            const float t = rays.t[i];
            if (!(t >= h.tNear && t <= h.tFar)) continue;
            const int bin = bins.binOf(t);
            ++h.counts[std::size_t(bin)];
            int &slot = slotOfLayer[rays.layer[i]];
            if (slot < 0) {
                slot = int(byFirstUse.size());
                LayerDepths entry;
                entry.layer = rays.layer[i];
                if (const Layer *known = layerTable.find(entry.layer)) entry.name = known->name;
                entry.counts.assign(std::size_t(bins.count), 0);
                entry.nearest = entry.farthest = t;
                byFirstUse.push_back(std::move(entry));
            }
            LayerDepths &layer = byFirstUse[std::size_t(slot)];
            ++layer.counts[std::size_t(bin)];
            ++layer.crossings;
            if (i == rays.begin[r]) ++layer.firstHits;
            layer.nearest = std::min(layer.nearest, t);
            layer.farthest = std::max(layer.farthest, t);
            sorted.push_back(t);
            ++h.crossings;
        }
    }
    for (int id = 0; id < kLayerSlots; ++id)
        if (slotOfLayer[std::size_t(id)] >= 0) h.layers.push_back(std::move(byFirstUse[std::size_t(slotOfLayer[std::size_t(id)])]));
    if (h.crossings == 0) {
        h.counts.clear(); // every crossing outside a fixed range
        return h;
    }

    std::sort(sorted.begin(), sorted.end());
    // before[i]: crossings in bins < i, i.e. where bin i starts in `sorted`.
    std::vector<uint64_t> before(h.counts.size() + 1, 0);
    for (std::size_t i = 0; i < h.counts.size(); ++i) before[i + 1] = before[i] + h.counts[i];

    std::vector<DepthSuggestion> suggestions;
    addEmptyRunSuggestions(h, rays, sorted, before, double(settings.nearEmptyFraction) * double(h.raysHit), suggestions);
    addLayerTransitionSuggestions(h, sorted, suggestions);
    for (DepthSuggestion &s : suggestions) measureSeparation(rays, s);
    std::erase_if(suggestions, [](const DepthSuggestion &s) { return s.raysSeparated == 0; });
    std::sort(suggestions.begin(), suggestions.end(), [](const DepthSuggestion &a, const DepthSuggestion &b) {
        if (a.raysSeparated != b.raysSeparated) return a.raysSeparated > b.raysSeparated;
        return a.distance < b.distance;
    });
    if (suggestions.size() > std::size_t(std::max(settings.maxSuggestions, 0)))
        suggestions.resize(std::size_t(std::max(settings.maxSuggestions, 0)));
    h.suggestions = std::move(suggestions);
    return h;
}

} // namespace mvcl::detail
