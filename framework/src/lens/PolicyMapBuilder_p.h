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

    /// One thread at a time: appends a blend of the `count` terms termAt(0), termAt(1), ...
    /// (weights > 0 that sum to 1, at least two) and returns its mix index. No pixel uses it
    /// yet. The terms come one by one from termAt, which builds each in registers: a handful
    /// per blend is too few for a memcpy, and a staging array read back whole would stall on
    /// its field-by-field stores.
    template <class TermAt> uint32_t appendBlend(uint32_t count, TermAt termAt) {
        const uint32_t first = uint32_t(m_map.m_terms.size());
        for (uint32_t i = 0; i < count; ++i) m_map.m_terms.push_back(termAt(i));
        m_map.m_mixes.push_back({first, count});
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
