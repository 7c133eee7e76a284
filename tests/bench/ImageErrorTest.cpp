// The convergence bench's pixel metrics on images whose errors are known in closed form.

#include "ImageError.h"

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace mvcl;
using namespace mvcl::bench;

namespace {

Framebuffer flat(int w, int h, glm::vec3 colour) {
    Framebuffer image(w, h);
    for (glm::vec3 &p : image.pixels()) p = colour;
    return image;
}

} // namespace

TEST(ImageError, IdenticalImagesHaveNoError) {
    Framebuffer image(5, 3);
    for (std::size_t i = 0; i < image.pixels().size(); ++i) image.pixels()[i] = glm::vec3(0.1f * float(i), 0.3f, 2.f);
    EXPECT_EQ(rootMeanSquaredError(image, image), 0.0);
    EXPECT_EQ(relativeMeanSquaredError(image, image), 0.0);
    EXPECT_TRUE(std::isinf(peakSignalToNoiseRatio(image, image)));
}

TEST(ImageError, ConstantOffset) {
    const Framebuffer reference = flat(4, 4, glm::vec3(0.5f));
    const Framebuffer image = flat(4, 4, glm::vec3(0.6f));
    const double d = double(0.6f) - double(0.5f);
    EXPECT_NEAR(rootMeanSquaredError(image, reference), d, 1e-12);
    EXPECT_NEAR(relativeMeanSquaredError(image, reference), d * d / (0.25 + 0.01), 1e-12);
    EXPECT_NEAR(peakSignalToNoiseRatio(image, reference), -10.0 * std::log10(d * d), 1e-9); // ≈ 20 dB
}

TEST(ImageError, MeanIsOverPixelsAndChannels) {
    const Framebuffer reference = flat(2, 2, glm::vec3(0.f));
    Framebuffer image = reference;
    image.at(1, 0).g = 1.f; // one channel of one pixel of four: MSE = 1/12
    EXPECT_NEAR(rootMeanSquaredError(image, reference), std::sqrt(1.0 / 12.0), 1e-12);
    EXPECT_NEAR(relativeMeanSquaredError(image, reference), 1.0 / 12.0 / 0.01, 1e-9);
    EXPECT_NEAR(peakSignalToNoiseRatio(image, reference), 10.0 * std::log10(12.0), 1e-9);
}

TEST(ImageError, RelativeErrorWeighsDarkPixelsMore) {
    const Framebuffer dark = flat(1, 1, glm::vec3(0.1f)), bright = flat(1, 1, glm::vec3(1.f));
    const Framebuffer darkOff = flat(1, 1, glm::vec3(0.2f)), brightOff = flat(1, 1, glm::vec3(1.1f));
    EXPECT_GT(relativeMeanSquaredError(darkOff, dark), 10.0 * relativeMeanSquaredError(brightOff, bright));
}

TEST(ImageError, PsnrClampsToTheDisplayRange) {
    const Framebuffer reference = flat(3, 3, glm::vec3(1.f));
    const Framebuffer image = flat(3, 3, glm::vec3(1.5f)); // both show as white
    EXPECT_TRUE(std::isinf(peakSignalToNoiseRatio(image, reference)));
    EXPECT_NEAR(rootMeanSquaredError(image, reference), 0.5, 1e-12); // RMSE does not clamp
}

TEST(ImageError, SizesMustMatch) {
    EXPECT_THROW(rootMeanSquaredError(Framebuffer(2, 2), Framebuffer(2, 3)), Error);
}
