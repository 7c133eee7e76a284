#include <mvcl/lens/PolicyMap.h>

#include <mvcl/core/Error.h>

#include <algorithm>

namespace mvcl {

PolicyMap::PolicyMap(int width, int height, const PixelPolicy &base)
    : m_width(width), m_height(height),
      m_mixOfPixel(std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0)), 0) {
    addPolicy(base);
}

PolicyMap::PolicyMap(int width, int height, const RayPolicy &base)
    : PolicyMap(width, height, PixelPolicy{base, glm::mat3(1.f), 0}) {}

uint16_t PolicyMap::addPolicy(const PixelPolicy &policy) {
    if (m_policies.size() >= 0xffff) throw Error("policy map", "more than 65535 distinct policies in one view");
    m_policies.push_back(policy);
    m_singleMixOfPolicy.push_back(uint32_t(m_mixes.size()));
    m_mixes.push_back({uint32_t(m_terms.size()), 1});
    const uint16_t index = uint16_t(m_policies.size() - 1);
    m_terms.push_back({index, 1.f});
    return index;
}

void PolicyMap::setRun(int y, int x0, int x1, uint16_t policy) {
    if (x0 >= x1) return;
    const auto row = m_mixOfPixel.begin() + std::ptrdiff_t(offset(0, y));
    std::fill(row + x0, row + x1, m_singleMixOfPolicy[policy]);
}

void PolicyMap::setPixelBlend(int x, int y, std::span<const PolicyTerm> terms) {
    int kept = 0;
    uint16_t last = 0;
    for (const PolicyTerm &t : terms) {
        if (t.policy >= m_policies.size()) throw Error("policy map", "blend names a policy that does not exist");
        if (t.weight > 0.f) {
            ++kept;
            last = t.policy;
        }
    }
    if (kept == 0) throw Error("policy map", "a pixel blend needs at least one positive weight");
    if (kept == 1) {
        setPixel(x, y, last);
        return;
    }
    const uint32_t first = uint32_t(m_terms.size());
    m_terms.resize(m_terms.size() + terms.size());
    normaliseBlend(terms, std::span<PolicyTerm>(m_terms).subspan(first));
    m_terms.resize(first + std::size_t(kept));
    m_mixOfPixel[offset(x, y)] = uint32_t(m_mixes.size());
    m_mixes.push_back({first, uint32_t(kept)});
}

uint16_t PolicyMap::dominantPolicyIndex(int x, int y) const {
    const std::span<const PolicyTerm> mix = terms(x, y);
    const auto best = std::max_element(mix.begin(), mix.end(), [](const PolicyTerm &a, const PolicyTerm &b) {
        return a.weight < b.weight;
    });
    return best->policy;
}

PolicyMap PolicyMap::splice(const PolicyMap &left, const PolicyMap &right, int column, int rightLensOffset) {
    if (left.m_width != right.m_width || left.m_height != right.m_height)
        throw Error("policy map", "cannot splice maps of different sizes");
    if (left.m_policies.size() + right.m_policies.size() > 0xffff)
        throw Error("policy map", "more than 65535 distinct policies in one view");
    PolicyMap spliced = left;
    const uint16_t policyOffset = uint16_t(left.m_policies.size());
    const uint32_t mixOffset = uint32_t(left.m_mixes.size());
    const uint32_t termOffset = uint32_t(left.m_terms.size());
    for (PixelPolicy policy : right.m_policies) {
        policy.lensSet = rightLensOffset >= 64 ? 0 : policy.lensSet << unsigned(rightLensOffset);
        spliced.m_policies.push_back(policy);
    }
    for (PolicyTerm term : right.m_terms) {
        term.policy = uint16_t(term.policy + policyOffset);
        spliced.m_terms.push_back(term);
    }
    for (const Mix &mix : right.m_mixes) spliced.m_mixes.push_back({mix.first + termOffset, mix.count});
    for (uint32_t mix : right.m_singleMixOfPolicy) spliced.m_singleMixOfPolicy.push_back(mix + mixOffset);
    const int split = std::clamp(column, 0, left.m_width);
    for (int y = 0; y < left.m_height; ++y) {
        const std::size_t row = left.offset(0, y);
        for (int x = split; x < left.m_width; ++x)
            spliced.m_mixOfPixel[row + std::size_t(x)] = right.m_mixOfPixel[row + std::size_t(x)] + mixOffset;
    }
    spliced.m_droppedClipVolumes = left.m_droppedClipVolumes + right.m_droppedClipVolumes;
    return spliced;
}

std::size_t PolicyMap::blendedPixelCount() const {
    return std::size_t(std::count_if(m_mixOfPixel.begin(), m_mixOfPixel.end(),
                                     [this](uint32_t mix) { return m_mixes[mix].count > 1; }));
}

} // namespace mvcl
