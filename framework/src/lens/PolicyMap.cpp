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

std::size_t PolicyMap::blendedPixelCount() const {
    return std::size_t(std::count_if(m_mixOfPixel.begin(), m_mixOfPixel.end(),
                                     [this](uint32_t mix) { return m_mixes[mix].count > 1; }));
}

} // namespace mvcl
