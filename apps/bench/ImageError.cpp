#include "ImageError.h"

#include <mvcl/core/Error.h>
#include <mvcl/view/ImageIO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace mvcl::bench {

namespace {

/// Mean over pixels and channels of term(image value, reference value), summed in double in a
/// fixed order so that the result does not depend on anything but the two images.
template <class Term>
double meanOverChannels(const Framebuffer &image, const Framebuffer &reference, Term term) {
    requireSameSize(image, reference);
    const auto &a = image.pixels();
    const auto &b = reference.pixels();
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c) sum += term(double(a[i][c]), double(b[i][c]));
    return a.empty() ? 0.0 : sum / (3.0 * double(a.size()));
}

} // namespace

void requireSameSize(const Framebuffer &image, const Framebuffer &reference) {
    if (image.width() != reference.width() || image.height() != reference.height())
        throw Error("image error", "sizes differ: " + std::to_string(image.width()) + "x" +
                                       std::to_string(image.height()) + " against reference " +
                                       std::to_string(reference.width()) + "x" +
                                       std::to_string(reference.height()));
}

double rootMeanSquaredError(const Framebuffer &image, const Framebuffer &reference) {
    return std::sqrt(meanOverChannels(image, reference, [](double i, double r) { return (i - r) * (i - r); }));
}

double relativeMeanSquaredError(const Framebuffer &image, const Framebuffer &reference, double epsilon) {
    return meanOverChannels(image, reference,
                            [epsilon](double i, double r) { return (i - r) * (i - r) / (r * r + epsilon); });
}

double peakSignalToNoiseRatio(const Framebuffer &image, const Framebuffer &reference) {
    const double mse = meanOverChannels(image, reference, [](double i, double r) {
        const double d = std::clamp(i, 0.0, 1.0) - std::clamp(r, 0.0, 1.0);
        return d * d;
    });
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return -10.0 * std::log10(mse);
}

LevelDifference levelDifference(const Framebuffer &image, const Framebuffer &reference, int threshold) {
    requireSameSize(image, reference);
    const auto level = [](float v) { return int(std::lround(linearToSrgb(v) * 255.f)); };
    const auto &a = image.pixels();
    const auto &b = reference.pixels();
    LevelDifference d;
    d.threshold = threshold;
    long long sum = 0, above = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        int largest = 0;
        for (int c = 0; c < 3; ++c) {
            const int difference = std::abs(level(a[i][c]) - level(b[i][c]));
            largest = std::max(largest, difference);
            sum += difference;
        }
        d.max = std::max(d.max, largest);
        above += largest > threshold;
    }
    if (!a.empty()) {
        d.mean = double(sum) / (3.0 * double(a.size()));
        d.shareAbove = double(above) / double(a.size());
    }
    return d;
}

} // namespace mvcl::bench
