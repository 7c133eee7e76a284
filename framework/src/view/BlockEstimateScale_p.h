#pragma once

#include <array>
#include <bit>
#include <cstdint>

namespace mvcl::detail {

/// The largest sample count the tables below hold.
inline constexpr uint32_t kBlockEstimateScaleCounts = 4096;

/// Per sample count n, E[e²] / E[v] for a pixel crossed by an edge: the squared error e² of the
/// mean of its first n samples over PixelSamples' two-block variance estimate v. The blocks
/// are runs of one R2 sequence, not independent samples: how much of their error cancels in
/// the mean depends on n (at 64 samples v overstates the error 2.7×, just past a power of two,
/// where the second block has a few samples, up to 70×). Computed by
/// scripts/block-estimate-scale.py (*EstimateScaleTable.cpp, generated); edges are what
/// carries an image's error, and images measured against converged references over-estimate
/// by the same factors (docs/benchmarks.md).
extern const std::array<float, kBlockEstimateScaleCounts + 1> kBlockEstimateScale;
/// The same for the earlier look (n ≥ 4): E[e²] at n over E[w], w the variance of the mean of
/// the first block's p samples from its two halves.
extern const std::array<float, kBlockEstimateScaleCounts + 1> kEarlierEstimateScale;
/// The same for the later look (n ≥ 4): E[e²] at n over E[g], g the variance from the two
/// halves of the second half of the first 2^m samples (2^m the largest power of two ≤ n).
extern const std::array<float, kBlockEstimateScaleCounts + 1> kLaterEstimateScale;

/// table[count]; beyond the table, the entry at the same place in its last octave (the pattern
/// repeats per octave, though the peak just past a power of two keeps growing: there the
/// estimate stays on the high side).
inline float estimateScale(const std::array<float, kBlockEstimateScaleCounts + 1> &table, uint32_t count) {
    if (count <= kBlockEstimateScaleCounts) return table[count];
    const uint32_t octave = std::bit_floor(count);
    const int shift = std::countr_zero(octave) - std::countr_zero(kBlockEstimateScaleCounts / 2);
    return table[kBlockEstimateScaleCounts / 2 + ((count - octave) >> shift)];
}

} // namespace mvcl::detail
