#include <mvcl/lens/LensStack.h>

#include "PolicyMapComposer_p.h"

#include <mvcl/core/Error.h>

namespace mvcl {

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

namespace {
// One snapshot per lens for the whole frame: a commit from another thread cannot tear it.
LensSnapshots snapshotsOf(const std::vector<std::shared_ptr<Lens>> &lenses) {
    LensSnapshots snapshots;
    snapshots.reserve(lenses.size());
    for (const auto &lens : lenses) snapshots.push_back(lens->snapshot());
    return snapshots;
}
} // namespace

PixelPolicy LensStack::composeSet(const RayPolicy &base, uint64_t lensSet) const {
    if (size() < 64 && (lensSet >> size()) != 0) throw Error("lens stack", "lens set names lenses the stack does not have");
    return PolicyMapComposer::policyOfSet(snapshotsOf(m_lenses), base, lensSet);
}

PolicyMap LensStack::compose(const RayPolicy &base, int width, int height, int threads) const {
    const LensSnapshots snapshots = snapshotsOf(m_lenses);
    return PolicyMapComposer(snapshots, base, width, height).compose(threads);
}

PolicyMap LensStack::compose(const LensContext &context, const RayPolicy &base, int threads) const {
    LensSnapshots snapshots;
    snapshots.reserve(m_lenses.size());
    for (const auto &lens : m_lenses) snapshots.push_back(lens->snapshotIn(context));
    return PolicyMapComposer(snapshots, base, context.imageWidth, context.imageHeight).compose(threads);
}

void LensStack::checkClipVolumes(const PolicyMap &map) {
    if (map.droppedClipVolumes() > 0)
        throw Error("lens stack", "overlapping lenses ask for more than " + std::to_string(kMaxClipVolumes) +
                                      " clip volumes on one ray type; " + std::to_string(map.droppedClipVolumes()) +
                                      " could not be merged and would be left out (use fewer clip lenses "
                                      "over the same pixels)");
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
