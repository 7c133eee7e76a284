#pragma once
/// \file LensSetIndex_p.h
/// Private to policy composition: numbers lens sets (64-bit masks) in the order they are first
/// seen. compose() looks a set up for every run and every blended term, so this is a small
/// open-addressing table (a few sets per row band) with the last answer cached in front, not a
/// node-based map.

#include <cstdint>
#include <utility>
#include <vector>

namespace mvcl {

class LensSetIndex {
public:
    static constexpr uint32_t kNone = 0xffffffffu;

    LensSetIndex() { m_slots.assign(kInitialSlots, Slot{}); }

    /// The set's number (0, 1, 2, ... in first-seen order) and whether this call added it.
    std::pair<uint32_t, bool> insert(uint64_t set) {
        if (set == m_lastSet && m_lastIndex != kNone) return {m_lastIndex, false};
        const std::size_t mask = m_slots.size() - 1;
        for (std::size_t slot = hash(set) & mask;; slot = (slot + 1) & mask) {
            Slot &s = m_slots[slot];
            if (s.index == kNone) {
                s = {set, uint32_t(m_sets.size())};
                m_sets.push_back(set);
                remember(set, s.index);
                if (2 * m_sets.size() > m_slots.size()) grow();
                return {uint32_t(m_sets.size() - 1), true};
            }
            if (s.set == set) {
                remember(set, s.index);
                return {s.index, false};
            }
        }
    }

    /// The sets in first-seen order (index → set).
    const std::vector<uint64_t> &sets() const { return m_sets; }

private:
    struct Slot {
        uint64_t set = 0;
        uint32_t index = kNone;
    };
    static constexpr std::size_t kInitialSlots = 64; // a power of two

    static std::size_t hash(uint64_t set) {
        // Fibonacci hashing: lens sets differ in a few low bits, the multiply spreads them.
        return std::size_t((set * 0x9e3779b97f4a7c15ull) >> 32);
    }
    void remember(uint64_t set, uint32_t index) {
        m_lastSet = set;
        m_lastIndex = index;
    }
    void grow() {
        std::vector<Slot> old(2 * m_slots.size());
        old.swap(m_slots);
        const std::size_t mask = m_slots.size() - 1;
        for (const Slot &s : old) {
            if (s.index == kNone) continue;
            std::size_t slot = hash(s.set) & mask;
            while (m_slots[slot].index != kNone) slot = (slot + 1) & mask;
            m_slots[slot] = s;
        }
    }

    std::vector<Slot> m_slots;
    std::vector<uint64_t> m_sets;
    uint64_t m_lastSet = 0;
    uint32_t m_lastIndex = kNone;
};

} // namespace mvcl
