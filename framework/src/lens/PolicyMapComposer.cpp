#include "PolicyMapComposer_p.h"

#include "LensSetIndex_p.h"
#include "PolicyMapBuilder_p.h"

#include <mvcl/core/WorkerPool.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/lens/PolicyComposition.h>

#include <algorithm>
#include <array>
#include <bit>
#include <unordered_map>

namespace mvcl {

namespace {

constexpr int kMaxBlended = LensStack::kMaxBlendedLenses;
constexpr int kMaxSubsets = 1 << kMaxBlended;
// Rows per parallel chunk: enough bands for every thread to take a few, few enough that
// the per-band bookkeeping (set tables, record vectors) stays negligible.
constexpr int kRowsPerBand = 16;

uint64_t lensBit(int lens) { return uint64_t(1) << lens; }

/// A boundary of a lens's row span. At equal x, events apply in this order, so that a lens
/// whose edge part is empty goes straight from out to in (and back) without a stale state.
enum class SpanEvent : uint8_t { Enter = 0, EnterInner = 1, LeaveInner = 2, Leave = 3 };

/// x, then event kind, then lens: sorting the packed keys sorts the events.
uint64_t eventKey(int x, SpanEvent event, int lens) {
    return (uint64_t(uint32_t(x)) << 8) | (uint64_t(event) << 6) | uint64_t(lens);
}
int eventX(uint64_t key) { return int(key >> 8); }
SpanEvent eventKind(uint64_t key) { return SpanEvent((key >> 6) & 3u); }
int eventLens(uint64_t key) { return int(key & 63u); }

} // namespace

/// What one band of rows found, in scan order; lens sets are band-local numbers until the
/// merge gives them policies.
class PolicyMapComposer::Band {
public:
    struct Run {
        int y, x0, x1;
        uint32_t set;
    };
    struct Blend {
        int y, x;
        uint32_t firstTerm; // into terms
        uint32_t termCount; // ≥ 2
        uint32_t mix = 0;   // set by the merge
    };
    struct Term {
        uint32_t set;
        float weight; // normalised
    };

    /// The set's band-local number; the first time, notes how many blends came before it,
    /// which is where its policy's own mix goes between the blends' mixes (as serial
    /// addPolicy and setPixelBlend calls would have ordered them).
    uint32_t see(uint64_t set) {
        const auto [index, added] = m_sets.insert(set);
        if (added) blendsBeforeSet.push_back(uint32_t(blends.size()));
        return index;
    }
    /// Pixels [x0, x1) of row y are on `set`; extends the previous run where it can.
    void addRun(int y, int x0, int x1, uint64_t set) {
        const uint32_t index = see(set);
        if (!runs.empty()) {
            Run &last = runs.back();
            if (last.y == y && last.x1 == x0 && last.set == index) {
                last.x1 = x1;
                return;
            }
        }
        runs.push_back({y, x0, x1, index});
    }
    const std::vector<uint64_t> &sets() const { return m_sets.sets(); }
    std::vector<uint32_t> blendsBeforeSet; // per band-local set
    std::vector<Run> runs;
    std::vector<Blend> blends;
    std::vector<Term> terms;
    std::vector<uint64_t> events; // scratch of scanRow
    // Scratch of scanRow: one row of coverage per active lens, and where each lens's row is.
    std::unique_ptr<float[]> coverage;
    std::array<const float *, LensStack::kMaxLenses> coverageOfLens{};

    std::vector<uint16_t> policyOfSet; // band-local set → map policy, set by the merge

private:
    LensSetIndex m_sets;
};

PolicyMapComposer::PolicyMapComposer(const LensSnapshots &snapshots, const RayPolicy &base, int width, int height)
    : m_snapshots(snapshots), m_base(base), m_width(width), m_height(height) {
    m_firstRow = height;
    for (int i = 0; i < int(snapshots.size()); ++i) {
        const LensSnapshot &s = *snapshots[size_t(i)];
        if (!s.enabled || s.contribution.isIdentity()) continue;
        const PixelRect r = s.region.pixelBounds(width, height);
        if (r.isEmpty()) continue;
        // An idempotent lens right above an equal one (same contribution, same region) adds
        // nothing: leaving it out keeps a feathered edge at coverage c instead of 1 − (1 − c)².
        if (!m_active.empty()) {
            const LensSnapshot &below = *snapshots[size_t(m_active.back().index)];
            if (s.idempotent && below.idempotent && s.region == below.region && s.contribution == below.contribution)
                continue;
        }
        m_active.push_back({i, r, &s.region});
        m_firstRow = std::min(m_firstRow, r.y0);
        m_endRow = std::max(m_endRow, r.y1);
    }
}

PixelPolicy PolicyMapComposer::policyOfSet(const LensSnapshots &snapshots, const RayPolicy &base, uint64_t lensSet,
                                           int *droppedClips) {
    PixelPolicy policy{base, glm::mat3(1.f), 0};
    for (uint64_t bits = lensSet; bits != 0; bits &= bits - 1)
        policy = applyContribution(policy, snapshots[size_t(std::countr_zero(bits))]->contribution, droppedClips);
    policy.lensSet = lensSet;
    return policy;
}

PolicyMap PolicyMapComposer::compose(int threads) const {
    PolicyMap map(m_width, m_height, m_base);
    if (m_active.empty()) return map;

    const int rows = m_endRow - m_firstRow;
    std::vector<Band> bands(size_t((rows + kRowsPerBand - 1) / kRowsPerBand));
    parallelForChunks(bands.size(), threads, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            // Left uninitialised: every entry read is written first, for the row that reads it.
            bands[b].coverage.reset(new float[m_active.size() * std::size_t(m_width)]);
            const int y0 = m_firstRow + int(b) * kRowsPerBand;
            const int y1 = std::min(m_endRow, y0 + kRowsPerBand);
            for (int y = y0; y < y1; ++y) scanRow(y, bands[b]);
            bands[b].coverage.reset();
        }
    });
    mergeBands(bands, map);
    parallelForChunks(bands.size(), threads, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) fillBand(bands[b], map);
    });
    return map;
}

void PolicyMapComposer::scanRow(int y, Band &band) const {
    std::vector<uint64_t> &events = band.events;
    events.clear();
    for (std::size_t k = 0; k < m_active.size(); ++k) {
        const ActiveLens &lens = m_active[k];
        if (y < lens.bounds.y0 || y >= lens.bounds.y1) continue;
        const LensRegion::RowSpan span = lens.region->rowSpan(y, m_width, m_height);
        if (span.x0 >= span.x1) continue;
        // The lens's coverage on its edge parts, for the whole row at once: both edges of an
        // ellipse batch into full SIMD lanes. Row buffer k is indexed by x.
        float *row = band.coverage.get() + k * std::size_t(m_width);
        lens.region->edgeCoverage(y, span, m_width, m_height, std::span(row + span.x0, std::size_t(span.x1 - span.x0)));
        band.coverageOfLens[size_t(lens.index)] = row;
        events.push_back(eventKey(span.x0, SpanEvent::Enter, lens.index));
        if (span.innerX0 < span.innerX1) {
            events.push_back(eventKey(span.innerX0, SpanEvent::EnterInner, lens.index));
            events.push_back(eventKey(span.innerX1, SpanEvent::LeaveInner, lens.index));
        }
        events.push_back(eventKey(span.x1, SpanEvent::Leave, lens.index));
    }
    std::sort(events.begin(), events.end());

    // Sweep: between consecutive boundaries each lens is out, in (fullSet) or on its edge.
    uint64_t fullSet = 0, edgeSet = 0;
    for (std::size_t e = 0; e < events.size();) {
        const int x = eventX(events[e]);
        for (; e < events.size() && eventX(events[e]) == x; ++e) {
            const uint64_t bit = lensBit(eventLens(events[e]));
            switch (eventKind(events[e])) {
            case SpanEvent::Enter: edgeSet |= bit; break;
            case SpanEvent::EnterInner:
                edgeSet &= ~bit;
                fullSet |= bit;
                break;
            case SpanEvent::LeaveInner:
                fullSet &= ~bit;
                edgeSet |= bit;
                break;
            case SpanEvent::Leave: edgeSet &= ~bit; break;
            }
        }
        if (e == events.size()) break;
        const int next = eventX(events[e]);
        if (edgeSet == 0) {
            if (fullSet != 0) band.addRun(y, x, next, fullSet);
        } else {
            scanEdgePixels(y, x, next, fullSet, edgeSet, band);
        }
    }
}

void PolicyMapComposer::scanEdgePixels(int y, int x0, int x1, uint64_t fullSet, uint64_t edgeSet, Band &band) const {
    // The lenses to ask, bottom → top: partly covering lenses are blended in this order, and
    // past kMaxBlended the upper ones are rounded, exactly as a pixel-by-pixel scan does.
    std::array<int, LensStack::kMaxLenses> edgeLens;
    std::array<const float *, LensStack::kMaxLenses> edgeCoverage; // each one's row, by x
    int edgeCount = 0;
    for (uint64_t bits = edgeSet; bits != 0; bits &= bits - 1) {
        const int lens = std::countr_zero(bits);
        edgeLens[size_t(edgeCount)] = lens;
        edgeCoverage[size_t(edgeCount++)] = band.coverageOfLens[size_t(lens)];
    }
    // Neighbouring blended pixels mostly share their partly covering lenses: the sets of the
    // subsets and their band numbers are worked out again only when those change.
    uint64_t cachedSet = 0;
    uint32_t cachedLenses = 0; // 0: nothing cached
    std::array<uint64_t, kMaxSubsets> subsetSet;
    std::array<uint32_t, kMaxSubsets> subsetIndex;

    for (int x = x0; x < x1; ++x) {
        uint64_t set = fullSet;
        int partialCount = 0;
        std::array<int, kMaxBlended> partialLens{};
        std::array<float, kMaxBlended> partialWeight{};
        uint32_t partialLenses = 0; // byte j: partialLens[j] + 1, one word to compare
        for (int k = 0; k < edgeCount; ++k) {
            const int lens = edgeLens[size_t(k)];
            const float weight = edgeCoverage[size_t(k)][x];
            if (weight >= 1.f) {
                set |= lensBit(lens);
            } else if (weight > 0.f) {
                if (partialCount < kMaxBlended) {
                    partialLenses |= uint32_t(lens + 1) << (8 * partialCount);
                    partialLens[size_t(partialCount)] = lens;
                    partialWeight[size_t(partialCount++)] = weight;
                } else if (weight >= 0.5f) {
                    set |= lensBit(lens); // past the exact blend: round to in or out
                }
            }
        }
        if (partialCount == 0) {
            if (set != 0) band.addRun(y, x, x + 1, set);
            continue;
        }
        // Every subset of the partly covering lenses, weighted by the chance that exactly
        // those apply: an exact blend of the images with and without each. Every subset's set
        // is seen, even one whose weight rounds to 0, as the serial scan composes its policy.
        const int subsets = 1 << partialCount;
        if (set != cachedSet || partialLenses != cachedLenses) {
            for (int subset = 0; subset < subsets; ++subset) {
                uint64_t s = set;
                for (int j = 0; j < partialCount; ++j)
                    if ((subset >> j) & 1) s |= lensBit(partialLens[size_t(j)]);
                subsetSet[size_t(subset)] = s;
                subsetIndex[size_t(subset)] = band.see(s);
            }
            cachedSet = set;
            cachedLenses = partialLenses;
        }
        if (partialCount == 1) {
            // The common case, one feathered edge: the general code below computes weights
            // 1·(1 − w) and 1·w, both > 0 as 0 < w < 1, and divides each by 0 + (1 − w) + w.
            // The same operations, without the loops.
            const float weight = partialWeight[0], outside = 1.f - weight;
            const float total = outside + weight;
            band.blends.push_back({y, x, uint32_t(band.terms.size()), 2, 0});
            band.terms.push_back({subsetIndex[0], outside / total});
            band.terms.push_back({subsetIndex[1], weight / total});
            continue;
        }
        std::array<PolicyTerm, kMaxSubsets> raw;
        for (int subset = 0; subset < subsets; ++subset) {
            float weight = 1.f;
            for (int j = 0; j < partialCount; ++j)
                weight *= (subset >> j) & 1 ? partialWeight[size_t(j)] : 1.f - partialWeight[size_t(j)];
            raw[size_t(subset)] = {uint16_t(subset), weight}; // policy = subset until the merge
        }
        std::array<PolicyTerm, kMaxSubsets> normalised;
        const std::size_t kept = PolicyMapBuilder::normaliseBlend(std::span(raw.data(), size_t(subsets)), normalised);
        // The empty subset's weight, a product of at most 4 factors ≥ 2⁻²⁴, never rounds to 0,
        // so at least one term is kept.
        if (kept == 1) {
            band.addRun(y, x, x + 1, subsetSet[normalised[0].policy]);
            continue;
        }
        band.blends.push_back({y, x, uint32_t(band.terms.size()), uint32_t(kept), 0});
        for (std::size_t i = 0; i < kept; ++i)
            band.terms.push_back({subsetIndex[normalised[i].policy], normalised[i].weight});
    }
}

void PolicyMapComposer::mergeBands(std::vector<Band> &bands, PolicyMap &map) const {
    PolicyMapBuilder builder(map);
    std::size_t blends = 0, terms = 0, sets = 0;
    for (const Band &band : bands) {
        blends += band.blends.size();
        terms += band.terms.size();
        sets += band.sets().size();
    }
    builder.reserve(sets + blends, sets + terms); // at most: every set is a new policy

    // Serial setPixelBlend calls would have appended each blend's mix after the policies of
    // the sets seen before it: walk each band's sets and blends in the order they were met.
    std::unordered_map<uint64_t, uint16_t> policyOf{{0, 0}};
    int droppedClips = 0;
    for (Band &band : bands) {
        band.policyOfSet.resize(band.sets().size());
        std::size_t next = 0; // the band's next blend to append
        const auto appendBlendsBefore = [&](std::size_t end) {
            for (; next < end; ++next) {
                Band::Blend &blend = band.blends[next];
                const Band::Term *terms = band.terms.data() + blend.firstTerm;
                const uint16_t *policyOfSet = band.policyOfSet.data(); // not reloaded per term
                blend.mix = builder.appendBlend(blend.termCount, [terms, policyOfSet](uint32_t i) {
                    return PolicyTerm{policyOfSet[terms[i].set], terms[i].weight};
                });
            }
        };
        for (std::size_t i = 0; i < band.sets().size(); ++i) {
            appendBlendsBefore(band.blendsBeforeSet[i]);
            const uint64_t set = band.sets()[i];
            const auto [it, added] = policyOf.try_emplace(set, 0);
            if (added) it->second = map.addPolicy(policyOfSet(m_snapshots, m_base, set, &droppedClips));
            band.policyOfSet[i] = it->second;
        }
        appendBlendsBefore(band.blends.size());
    }
    map.setDroppedClipVolumes(droppedClips);
}

void PolicyMapComposer::fillBand(const Band &band, PolicyMap &map) {
    for (const Band::Run &run : band.runs) map.setRun(run.y, run.x0, run.x1, band.policyOfSet[run.set]);
    PolicyMapBuilder builder(map);
    for (const Band::Blend &blend : band.blends) builder.setPixelMix(blend.x, blend.y, blend.mix);
}

} // namespace mvcl
