// The per-pixel error estimate of PixelSamples: two contiguous blocks of the pixel's samples,
// the first 2^m and the rest (at a power of two, the two halves), against sums worked out here.

#include "../../framework/src/view/PixelTracer_p.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mvcl::detail {
namespace {

PixelSamples samplesOf(const std::vector<float> &grey) {
    PixelSamples s;
    for (float v : grey) {
        s.add(s.count, glm::vec3(v));
        ++s.count;
    }
    return s;
}

/// What relativeMse() should be for grey values, with the first `a` samples as one block.
double expectedRelativeMse(const std::vector<float> &grey, size_t a) {
    const size_t n = grey.size(), b = n - a;
    double first = 0.0, second = 0.0;
    for (size_t i = 0; i < n; ++i) (i < a ? first : second) += grey[i];
    const double mean = (first + second) / double(n), d = first / double(a) - second / double(b);
    return d * d * double(a) * double(b) / double(n * n) / (mean * mean + 0.01);
}

TEST(PixelSamplesTest, BlocksAreTheFirstPowerOfTwoAndTheRest) {
    const std::vector<float> values{0.9f, 0.1f, 0.5f, 0.7f, 0.2f, 0.6f, 0.3f, 0.8f, 0.4f};
    // n: the first block's size (the largest power of two below n; n / 2 at a power of two).
    const std::vector<std::pair<size_t, size_t>> cases{{2, 1}, {3, 2}, {4, 2}, {5, 4}, {6, 4}, {7, 4}, {8, 4}, {9, 8}};
    for (const auto &[n, a] : cases) {
        const std::vector<float> grey(values.begin(), values.begin() + long(n));
        const PixelSamples s = samplesOf(grey);
        EXPECT_NEAR(s.relativeMse(), expectedRelativeMse(grey, a), 1e-6) << n << " samples";
    }
}

TEST(PixelSamplesTest, RelativeErrorIsTheStandardErrorOverTheSquareRootOfBrightness) {
    const std::vector<float> grey{0.2f, 0.6f, 0.4f, 0.4f, 0.1f, 0.3f};
    const PixelSamples s = samplesOf(grey);
    // Blocks of 4 and 2: means 0.4 and 0.2, overall 1/3.
    const double sigma = std::abs(0.4 - 0.2) * std::sqrt(4.0 * 2.0) / 6.0;
    EXPECT_NEAR(s.relativeError(), 3.0 * sigma / std::sqrt(1e-4 + 3.0 / 3.0), 1e-6);
    EXPECT_NEAR(s.mean().x, 2.0f / 6.0f, 1e-6f);
}

TEST(PixelSamplesTest, RelativeErrorKeepsTheEstimateOneLevelDown) {
    // Eight samples whose halves agree (means 0.5 and 0.5): the blocks alone say no error. One
    // level down, the first four's halves (0.7 and 0.3) disagree: the variance of a 4-sample
    // mean from them, 0.4² / 4, scaled to 8 samples as 1/n, is what the pixel reports.
    const PixelSamples s = samplesOf({0.9f, 0.5f, 0.1f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
    EXPECT_NEAR(s.relativeMse(), 0.0, 1e-9) << "the image's estimate stays the blocks' own";
    const double sigma = std::sqrt(0.4 * 0.4 / 4.0 * 4.0 / 8.0);
    EXPECT_NEAR(s.relativeError(), 3.0 * sigma / std::sqrt(1e-4 + 1.5), 1e-6);
    // Where the blocks see more than the earlier look, theirs is kept.
    const PixelSamples later = samplesOf({0.5f, 0.5f, 0.5f, 0.5f, 0.9f, 0.9f, 0.9f, 0.9f});
    EXPECT_NEAR(later.relativeError(), 3.0 * 0.4 * 0.5 / std::sqrt(1e-4 + 2.1), 1e-6);
}

TEST(PixelSamplesTest, NoEstimateBelowTwoSamples) {
    const PixelSamples one = samplesOf({0.5f});
    EXPECT_EQ(one.relativeError(), INFINITY);
    EXPECT_EQ(one.relativeMse(), 0.f);
    // Equal samples: no error, whatever the blocks.
    EXPECT_EQ(samplesOf({0.5f, 0.5f, 0.5f}).relativeMse(), 0.f);
}

} // namespace
} // namespace mvcl::detail
