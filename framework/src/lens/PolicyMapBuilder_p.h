#pragma once
/// \file PolicyMapBuilder_p.h
/// Private to policy composition: fills a PolicyMap's blends in two steps. PolicyMap::
/// setPixelBlend appends a blend to the map's tables and points its pixel at it in one go, so
/// blends could only be set one after the other. Here one thread appends the blends (in the
/// order serial setPixelBlend calls would have, interleaved with addPolicy), and then threads
/// point their pixels at them. The tables come out the same as from the serial calls, entry
/// for entry.

#include <mvcl/lens/PolicyMap.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace mvcl {

class PolicyMapBuilder {
public:
    explicit PolicyMapBuilder(PolicyMap &map) : m_map(map) {}

    /// Room for `mixes` more mixes and `terms` more terms, so that appending does not move them.
    void reserve(std::size_t mixes, std::size_t terms) {
        m_map.m_mixes.reserve(m_map.m_mixes.size() + mixes);
        m_map.m_terms.reserve(m_map.m_terms.size() + terms);
    }

    /// One thread at a time: appends a blend of `normalised` (weights > 0 that sum to 1, at
    /// least two terms) and returns its mix index. No pixel uses it yet.
    uint32_t appendBlend(std::span<const PolicyTerm> normalised) {
        const uint32_t first = uint32_t(m_map.m_terms.size());
        // One by one: a blend has a handful of terms, a memcpy call would cost more.
        for (const PolicyTerm &term : normalised) m_map.m_terms.push_back(term);
        m_map.m_mixes.push_back({first, uint32_t(normalised.size())});
        return uint32_t(m_map.m_mixes.size() - 1);
    }

    /// Any thread, each pixel from one thread only: pixel (x, y) uses mix `mix`.
    void setPixelMix(int x, int y, uint32_t mix) { m_map.m_mixOfPixel[m_map.offset(x, y)] = mix; }

    /// PolicyMap::setPixelBlend's normalisation, so a blend written here has the same weights.
    static std::size_t normaliseBlend(std::span<const PolicyTerm> terms, std::span<PolicyTerm> normalised) {
        return PolicyMap::normaliseBlend(terms, normalised);
    }

private:
    PolicyMap &m_map;
};

} // namespace mvcl
