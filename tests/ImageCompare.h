#pragma once
// Tolerant image comparison for golden tests: images differ in a pixel when any sRGB channel is
// off by more than `channelTolerance` (0..255); the test allows a small share of such pixels so
// that last-bit differences between compilers and CPUs do not fail it, while any real change does.

#include <mvcl/view/Framebuffer.h>
#include <mvcl/view/ImageIO.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace mvcl::test {

struct ImageDifference {
    double differingFraction = 1.0; ///< share of pixels off by more than the tolerance
    int maxChannelDelta = 255;      ///< largest sRGB channel difference seen, 0..255
};

inline ImageDifference compareImages(const Framebuffer &a, const Framebuffer &b, int channelTolerance) {
    ImageDifference diff;
    if (a.width() != b.width() || a.height() != b.height()) return diff;
    std::size_t differing = 0;
    diff.maxChannelDelta = 0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int va = int(std::lround(linearToSrgb(a.pixels()[i][c]) * 255.f));
            const int vb = int(std::lround(linearToSrgb(b.pixels()[i][c]) * 255.f));
            worst = std::max(worst, std::abs(va - vb));
        }
        diff.maxChannelDelta = std::max(diff.maxChannelDelta, worst);
        if (worst > channelTolerance) ++differing;
    }
    diff.differingFraction = double(differing) / double(std::max<std::size_t>(1, a.pixels().size()));
    return diff;
}

/// True when golden images should be (re)written instead of compared: MVCL_UPDATE_GOLDEN=1.
inline bool updateGoldenRequested() {
    const char *v = std::getenv("MVCL_UPDATE_GOLDEN");
    return v && std::string(v) == "1";
}

} // namespace mvcl::test

/// In a test body: compares the image file `rendered` with the file `golden` (a pixel differs
/// when a channel is off by more than 8 of 255; at most 0.2 % may), or, under
/// MVCL_UPDATE_GOLDEN=1, copies `rendered` over `golden` and skips the test.
#define MVCL_EXPECT_MATCHES_GOLDEN(rendered, golden)                                                              \
    do {                                                                                                          \
        if (::mvcl::test::updateGoldenRequested()) {                                                              \
            std::filesystem::copy_file((rendered), (golden), std::filesystem::copy_options::overwrite_existing); \
            GTEST_SKIP() << "wrote " << (golden);                                                                 \
        }                                                                                                         \
        ASSERT_TRUE(std::filesystem::exists(golden)) << (golden) << " is missing; run with MVCL_UPDATE_GOLDEN=1"; \
        const ::mvcl::test::ImageDifference goldenDiff =                                                          \
            ::mvcl::test::compareImages(::mvcl::readImage(rendered), ::mvcl::readImage(golden), 8);             \
        EXPECT_LT(goldenDiff.differingFraction, 0.002) << "max channel delta " << goldenDiff.maxChannelDelta;    \
    } while (false)
