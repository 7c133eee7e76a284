#pragma once
/// \file PolicyMapBuilder_p.h
/// Private to policy composition: fills a PolicyMap's blended pixels from several threads.
/// PolicyMap::setPixelBlend appends each blend to the map's tables, so blends would have to be
/// written one after the other. Here the composer first reserves room for every blend (on one
/// thread, interleaved with addPolicy exactly as serial setPixelBlend calls would have been),
/// and then threads write their blends into the reserved places. The tables come out the same
/// as from the serial calls, entry for entry.

#include <mvcl/lens/PolicyMap.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

namespace mvcl {

class PolicyMapBuilder {
public:
    explicit PolicyMapBuilder(PolicyMap &map) : m_map(map) {}

    /// Entries of the mix and term tables so far (reserved ones included).
    uint32_t mixCount() const { return uint32_t(m_map.m_mixes.size()); }
    uint32_t termCount() const { return uint32_t(m_map.m_terms.size()); }

    /// One thread at a time: appends room for `mixes` blends with `terms` terms in all.
    void reserveBlends(std::size_t mixes, std::size_t terms) {
        m_map.m_mixes.resize(m_map.m_mixes.size() + mixes, PolicyMap::Mix{0, 0});
        m_map.m_terms.resize(m_map.m_terms.size() + terms);
    }

    /// Any thread, each blend once: pixel (x, y) blends `normalised` (weights > 0 that sum to
    /// 1, at least two) stored at reserved mix `mix`, terms from `firstTerm` on.
    void setPixelBlendAt(int x, int y, uint32_t mix, uint32_t firstTerm, std::span<const PolicyTerm> normalised) {
        std::copy(normalised.begin(), normalised.end(), m_map.m_terms.begin() + firstTerm);
        m_map.m_mixes[mix] = {firstTerm, uint32_t(normalised.size())};
        m_map.m_mixOfPixel[m_map.offset(x, y)] = mix;
    }

    /// PolicyMap::setPixelBlend's normalisation, so a blend written here has the same weights.
    static std::size_t normaliseBlend(std::span<const PolicyTerm> terms, std::span<PolicyTerm> normalised) {
        return PolicyMap::normaliseBlend(terms, normalised);
    }

private:
    PolicyMap &m_map;
};

} // namespace mvcl
