#pragma once
/// \file PolicyMap.h
/// Per-pixel policies as data: a small table of distinct PixelPolicy entries (one per overlap
/// set; entry 0 is the base) and, per pixel, a mix of entries with weights. Inside lenses and
/// outside them a pixel has one term of weight 1; on a feathered edge it blends the policies
/// with and without the lens, and the renderer blends their radiance with those weights.

#include <mvcl/core/Export.h>

#include <mvcl/lens/PixelPolicy.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mvcl {

struct PolicyTerm {
    uint16_t policy = 0;
    float weight = 1.f;
};

class MVCL_EXPORT PolicyMap {
public:
    /// Every pixel starts on `base` (entry 0).
    explicit PolicyMap(int width, int height, const PixelPolicy &base = {});
    PolicyMap(int width, int height, const RayPolicy &base);

    int width() const { return m_width; }
    int height() const { return m_height; }

    /// Adds a policy and returns its index; throws mvcl::Error past 65535 entries.
    uint16_t addPolicy(const PixelPolicy &policy);
    const PixelPolicy &policy(uint16_t index) const { return m_policies[index]; }
    PixelPolicy &policy(uint16_t index) { return m_policies[index]; }
    const std::vector<PixelPolicy> &policies() const { return m_policies; }

    /// The pixel uses one policy with weight 1.
    void setPixel(int x, int y, uint16_t policy) {
        m_mixOfPixel[offset(x, y)] = m_singleMixOfPolicy[policy];
    }
    /// Pixels [x0, x1) of row y use one policy with weight 1. Rows are independent: threads
    /// may fill different rows (or disjoint runs) at the same time.
    void setRun(int y, int x0, int x1, uint16_t policy);
    /// The pixel blends several policies; weights (> 0) are normalised to sum to 1. Terms with
    /// weight ≤ 0 are dropped; a single remaining term is the same as setPixel.
    void setPixelBlend(int x, int y, std::span<const PolicyTerm> terms);

    /// The pixel's terms (at least one).
    std::span<const PolicyTerm> terms(int x, int y) const { return mixTerms(m_mixOfPixel[offset(x, y)]); }
    /// The policy with the largest weight at the pixel (the first of equal weights).
    const PixelPolicy &dominantPolicy(int x, int y) const { return m_policies[dominantPolicyIndex(x, y)]; }
    uint16_t dominantPolicyIndex(int x, int y) const;
    /// Index of the pixel's mix; pixels with equal indices render with the same policies.
    uint32_t mixIndex(int x, int y) const { return m_mixOfPixel[offset(x, y)]; }
    /// Number of pixels that blend two or more policies.
    std::size_t blendedPixelCount() const;

    /// Clip volumes that overlapping lenses asked for beyond kMaxClipVolumes per ray type and
    /// that could not be merged, summed over the map's policies: those policies cut less than
    /// their lenses asked. 0 for a map that renders exactly what its lenses say. Composition
    /// never throws for this; tools report it (mvcl-render fails, see LensStack::compose).
    int droppedClipVolumes() const { return m_droppedClipVolumes; }
    void setDroppedClipVolumes(int count) { m_droppedClipVolumes = count; }

    /// Two maps of one size side by side (a view comparing two lens stacks): columns x <
    /// `column` from `left`, the others from `right`. The table holds left's policies, then
    /// right's, whose lens sets are shifted up by `rightLensOffset` bits (lenses of the right
    /// stack counted after the left's; bits shifted past 64 are dropped). Throws mvcl::Error
    /// when the sizes differ or the tables together pass 65535 policies.
    static PolicyMap splice(const PolicyMap &left, const PolicyMap &right, int column, int rightLensOffset);

    /// Mixes by index, for loops that walk whole rows (comparing maps, rendering): the mix
    /// index of every pixel of row y, and a mix's terms.
    std::span<const uint32_t> rowMixIndices(int y) const {
        return {m_mixOfPixel.data() + offset(0, y), std::size_t(m_width)};
    }
    std::size_t mixCount() const { return m_mixes.size(); }
    std::span<const PolicyTerm> mixTerms(uint32_t mix) const {
        return {m_terms.data() + m_mixes[mix].first, m_mixes[mix].count};
    }

private:
    friend class PolicyMapBuilder; // LensStack::compose fills the mixes of many rows at once

    /// How a blend is normalised: the terms with weight > 0, in order, each divided by their
    /// sum, written to `normalised` (room for terms.size()). Returns how many were written.
    static std::size_t normaliseBlend(std::span<const PolicyTerm> terms, std::span<PolicyTerm> normalised) {
        float total = 0.f;
        for (const PolicyTerm &t : terms)
            if (t.weight > 0.f) total += t.weight;
        std::size_t kept = 0;
        for (const PolicyTerm &t : terms)
            if (t.weight > 0.f) normalised[kept++] = {t.policy, t.weight / total};
        return kept;
    }

    struct Mix {
        uint32_t first;
        uint32_t count;
    };
    std::size_t offset(int x, int y) const {
        return std::size_t(y) * std::size_t(m_width) + std::size_t(x);
    }

    int m_width;
    int m_height;
    std::vector<PixelPolicy> m_policies;
    std::vector<PolicyTerm> m_terms;
    std::vector<Mix> m_mixes;                  // single-policy mixes and blends, interleaved
    std::vector<uint32_t> m_singleMixOfPolicy; // policy index → its weight-1 mix
    std::vector<uint32_t> m_mixOfPixel;
    int m_droppedClipVolumes = 0;
};

} // namespace mvcl
