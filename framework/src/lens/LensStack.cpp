#include <mvcl/lens/LensStack.h>

#include <mvcl/core/Error.h>
#include <mvcl/lens/PolicyComposition.h>

#include <algorithm>
#include <array>
#include <bit>
#include <unordered_map>

namespace mvcl {

namespace {

using Snapshots = std::vector<std::shared_ptr<const LensSnapshot>>;

PixelPolicy composeFromSnapshots(const Snapshots &snapshots, const RayPolicy &base, uint64_t lensSet) {
    PixelPolicy policy{base, glm::mat3(1.f), 0};
    for (uint64_t bits = lensSet; bits != 0; bits &= bits - 1) {
        const int index = std::countr_zero(bits);
        policy = applyContribution(policy, snapshots[size_t(index)]->contribution);
    }
    policy.lensSet = lensSet;
    return policy;
}

/// What covers one pixel: lenses that apply fully, and those that apply in part (feather).
struct PixelCover {
    uint64_t fullSet = 0;
    int partialCount = 0;
    std::array<int, LensStack::kMaxBlendedLenses> partialLens{};
    std::array<float, LensStack::kMaxBlendedLenses> partialWeight{};
    bool touched = false;

    void add(int lens, float weight) {
        touched = true;
        if (weight >= 1.f) {
            fullSet |= uint64_t(1) << lens;
        } else if (weight > 0.f) {
            if (partialCount < LensStack::kMaxBlendedLenses) {
                partialLens[size_t(partialCount)] = lens;
                partialWeight[size_t(partialCount++)] = weight;
            } else if (weight >= 0.5f) {
                fullSet |= uint64_t(1) << lens; // past the exact blend: round to in or out
            }
        }
    }
};

} // namespace

const std::shared_ptr<Lens> &LensStack::lens(int index) const {
    if (index < 0 || index >= size()) throw Error("lens stack", "no lens at index " + std::to_string(index));
    return m_lenses[size_t(index)];
}

void LensStack::add(std::shared_ptr<Lens> lens) { insert(size(), std::move(lens)); }

void LensStack::insert(int index, std::shared_ptr<Lens> lens) {
    if (!lens) throw Error("lens stack", "cannot add a null lens");
    if (size() >= kMaxLenses)
        throw Error("lens stack", "a stack holds at most " + std::to_string(kMaxLenses) + " lenses");
    if (index < 0 || index > size()) throw Error("lens stack", "no position " + std::to_string(index));
    m_lenses.insert(m_lenses.begin() + index, std::move(lens));
}

void LensStack::remove(int index) {
    lens(index);
    m_lenses.erase(m_lenses.begin() + index);
}

void LensStack::move(int from, int to) {
    lens(from);
    lens(to);
    std::shared_ptr<Lens> moving = std::move(m_lenses[size_t(from)]);
    m_lenses.erase(m_lenses.begin() + from);
    m_lenses.insert(m_lenses.begin() + to, std::move(moving));
}

PixelPolicy LensStack::composeSet(const RayPolicy &base, uint64_t lensSet) const {
    Snapshots snapshots;
    for (const auto &lens : m_lenses) snapshots.push_back(lens->snapshot());
    if (size() < 64 && (lensSet >> size()) != 0) throw Error("lens stack", "lens set names lenses the stack does not have");
    return composeFromSnapshots(snapshots, base, lensSet);
}

PolicyMap LensStack::compose(const RayPolicy &base, int width, int height) const {
    PolicyMap map(width, height, base);
    // One snapshot per lens for the whole frame: a commit from another thread cannot tear it.
    Snapshots snapshots;
    std::vector<int> active;
    std::vector<PixelRect> bounds;
    for (int i = 0; i < size(); ++i) {
        snapshots.push_back(m_lenses[size_t(i)]->snapshot());
        const LensSnapshot &s = *snapshots.back();
        if (!s.enabled || s.contribution.isIdentity()) continue;
        const PixelRect r = s.region.pixelBounds(width, height);
        if (r.isEmpty()) continue;
        active.push_back(i);
        bounds.push_back(r);
    }
    if (active.empty()) return map;

    std::unordered_map<uint64_t, uint16_t> policyOfSet{{0, 0}};
    uint64_t lastSet = 0;
    uint16_t lastPolicy = 0;
    auto policyFor = [&](uint64_t set) {
        if (set == lastSet) return lastPolicy; // neighbouring pixels mostly share their set
        auto [it, inserted] = policyOfSet.try_emplace(set, 0);
        if (inserted) it->second = map.addPolicy(composeFromSnapshots(snapshots, base, set));
        lastSet = set;
        lastPolicy = it->second;
        return lastPolicy;
    };

    // Rows at a time: only pixels inside some lens's bounds are visited.
    std::vector<PixelCover> row(static_cast<size_t>(width));
    std::vector<PolicyTerm> terms;
    for (int y = 0; y < height; ++y) {
        int rowX0 = width, rowX1 = 0;
        for (size_t k = 0; k < active.size(); ++k) {
            const PixelRect &r = bounds[k];
            if (y < r.y0 || y >= r.y1) continue;
            const int lens = active[k];
            const LensRegion &region = snapshots[size_t(lens)]->region;
            const LensRegion::RowSpan span = region.rowSpan(y, width, height);
            auto addCoverage = [&](int x) {
                row[size_t(x)].add(lens, region.coverage({float(x) + 0.5f, float(y) + 0.5f}, width, height));
            };
            for (int x = span.x0; x < span.innerX0; ++x) addCoverage(x);
            for (int x = span.innerX0; x < span.innerX1; ++x) row[size_t(x)].add(lens, 1.f);
            for (int x = span.innerX1; x < span.x1; ++x) addCoverage(x);
            if (span.x0 < span.x1) {
                rowX0 = std::min(rowX0, span.x0);
                rowX1 = std::max(rowX1, span.x1);
            }
        }
        for (int x = rowX0; x < rowX1; ++x) {
            PixelCover &cover = row[size_t(x)];
            if (!cover.touched) continue;
            if (cover.partialCount == 0) {
                if (cover.fullSet != 0) map.setPixel(x, y, policyFor(cover.fullSet));
            } else {
                // Every subset of the partly covering lenses, weighted by the chance that
                // exactly those apply: an exact blend of the images with and without each.
                terms.clear();
                const int n = cover.partialCount;
                for (uint32_t subset = 0; subset < (1u << n); ++subset) {
                    uint64_t set = cover.fullSet;
                    float weight = 1.f;
                    for (int j = 0; j < n; ++j) {
                        const bool in = (subset >> j) & 1u;
                        if (in) set |= uint64_t(1) << cover.partialLens[size_t(j)];
                        weight *= in ? cover.partialWeight[size_t(j)] : 1.f - cover.partialWeight[size_t(j)];
                    }
                    terms.push_back({policyFor(set), weight});
                }
                map.setPixelBlend(x, y, terms);
            }
            cover = PixelCover{};
        }
    }
    return map;
}

std::vector<LensCost> LensStack::costs(const PolicyMap &map, std::span<const PolicyCost> perPolicy) const {
    std::vector<LensCost> result;
    for (int i = 0; i < size(); ++i) {
        LensCost cost;
        cost.index = i;
        cost.label = m_lenses[size_t(i)]->label();
        const uint64_t bit = uint64_t(1) << i;
        for (size_t p = 0; p < map.policies().size() && p < perPolicy.size(); ++p) {
            if ((map.policies()[p].lensSet & bit) == 0) continue;
            cost.pixels += perPolicy[p].pixels;
            cost.rays += perPolicy[p].rays;
            cost.milliseconds += perPolicy[p].milliseconds;
        }
        result.push_back(cost);
    }
    return result;
}

} // namespace mvcl
