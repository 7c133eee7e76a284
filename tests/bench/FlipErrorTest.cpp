// LDR-FLIP (Andersson et al. 2020) self-checks: zero for equal images, the paper's colour
// mapping on flat images (where the filters and feature detectors have nothing to do), the
// separable filters against the paper's 2-D filters, and orderings a perceptual metric must keep.

#include "FlipError.h"

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using namespace mvcl;
using namespace mvcl::bench;

namespace {

Framebuffer flat(int w, int h, glm::vec3 colour) {
    Framebuffer image(w, h);
    for (glm::vec3 &p : image.pixels()) p = colour;
    return image;
}

Framebuffer noisy(const Framebuffer &base, float amplitude, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-amplitude, amplitude);
    Framebuffer image = base;
    for (glm::vec3 &p : image.pixels()) p += glm::vec3(u(rng), u(rng), u(rng));
    return image;
}

/// A grey ramp with a sharp vertical edge: edges and points for the detectors to find.
Framebuffer scene(int w, int h) {
    Framebuffer image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            image.at(x, y) = x < w / 2 ? glm::vec3(0.1f + 0.3f * float(y) / float(h)) : glm::vec3(0.8f, 0.5f, 0.2f);
    return image;
}

/// The paper's 2-D edge/point filter (x direction), positive weights normalised to 1 and
/// negative ones to −1, applied with replicated borders: what the separable code must equal.
std::vector<double> bruteForceFeature(const std::vector<float> &luminance, int w, int h, double ppd, bool points,
                                      bool alongY) {
    const double sd = 0.5 * 0.082 * ppd;
    const int r = int(std::ceil(3.0 * sd));
    std::vector<double> k(std::size_t((2 * r + 1) * (2 * r + 1)));
    double positive = 0.0, negative = 0.0;
    for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i) {
            const double g = std::exp(-double(i * i + j * j) / (2.0 * sd * sd));
            const double v = points ? (double(i * i) / (sd * sd) - 1.0) * g : -double(i) * g;
            k[std::size_t((j + r) * (2 * r + 1) + i + r)] = v;
            (v > 0 ? positive : negative) += v;
        }
    for (double &v : k) v = v > 0 ? v / positive : v / -negative;
    std::vector<double> out(luminance.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0;
            for (int j = -r; j <= r; ++j)
                for (int i = -r; i <= r; ++i) {
                    const int sx = std::clamp(x + (alongY ? j : i), 0, w - 1);
                    const int sy = std::clamp(y + (alongY ? i : j), 0, h - 1);
                    sum += k[std::size_t((j + r) * (2 * r + 1) + i + r)] * luminance[std::size_t(sy * w + sx)];
                }
            out[std::size_t(y * w + x)] = sum;
        }
    return out;
}

} // namespace

TEST(FlipError, EqualImagesHaveNoError) {
    const Framebuffer image = noisy(scene(40, 30), 0.2f, 1);
    const std::vector<float> map = FlipReference(image).errorMap(image);
    EXPECT_EQ(*std::max_element(map.begin(), map.end()), 0.f);
}

TEST(FlipError, BlackAgainstWhiteFollowsTheColourMapping) {
    // Flat images: the CSF filters (unit sum, replicated borders) keep them as they are and no
    // feature is found, so FLIP is the redistributed HyAB distance of black and white:
    // L* 0 against 100, a* = b* = 0, HyAB = 100. The maximum distance is that of Hunt-adjusted
    // sRGB green (L*a*b* 87.737, −86.185, 83.181) and blue (32.303, 79.197, −107.864).
    const double green[3] = {87.737, -86.185 * 0.87737, 83.181 * 0.87737};
    const double blue[3] = {32.303, 79.197 * 0.32303, -107.864 * 0.32303};
    const double cmax =
        std::pow(std::fabs(green[0] - blue[0]) + std::hypot(green[1] - blue[1], green[2] - blue[2]), 0.7);
    const double distance = std::pow(100.0, 0.7);
    ASSERT_GT(distance, 0.4 * cmax); // in the compressed upper part of the range
    const double expected = 0.95 + (distance - 0.4 * cmax) / (cmax - 0.4 * cmax) * 0.05;
    const Framebuffer black = flat(24, 16, glm::vec3(0.f)), white = flat(24, 16, glm::vec3(1.f));
    EXPECT_NEAR(flipError(white, black), expected, 1e-3);
    EXPECT_NEAR(flipError(black, white), expected, 1e-3);
}

TEST(FlipError, SmallFlatDifferencesUseTheLinearPart) {
    // Grey 0.5 against 0.52: only L* differs; HyAB^0.7 is far below 0.4·cmax, mapped linearly.
    const Framebuffer a = flat(16, 16, glm::vec3(0.5f)), b = flat(16, 16, glm::vec3(0.52f));
    auto lightness = [](double y) { return 116.0 * std::cbrt(y) - 16.0; }; // y > (6/29)³
    const double green[3] = {87.737, -86.185 * 0.87737, 83.181 * 0.87737};
    const double blue[3] = {32.303, 79.197 * 0.32303, -107.864 * 0.32303};
    const double cmax =
        std::pow(std::fabs(green[0] - blue[0]) + std::hypot(green[1] - blue[1], green[2] - blue[2]), 0.7);
    const double expected = 0.95 / (0.4 * cmax) * std::pow(lightness(0.52) - lightness(0.5), 0.7);
    EXPECT_NEAR(flipError(b, a), expected, 2e-3);
}

TEST(FlipError, SeparableFeatureFiltersEqualThePapers2dFilters) {
    const int w = 37, h = 29;
    const Framebuffer image = noisy(scene(w, h), 0.3f, 7);
    const double ppd = kFlipDefaultPixelsPerDegree;
    const FlipReference::Prepared p = FlipReference(image, ppd).prepare(image);
    // The detectors see the clamped luminance Y / Y_white (sRGB Y weights).
    std::vector<float> luminance(image.pixels().size());
    for (std::size_t i = 0; i < luminance.size(); ++i) {
        const glm::vec3 c = glm::clamp(image.pixels()[i], 0.f, 1.f);
        luminance[i] = float((2613072.0 * c.r + 8788810.0 * c.g + 887015.0 * c.b) / 12288897.0);
    }
    for (const bool points : {false, true}) {
        const std::vector<double> dx = bruteForceFeature(luminance, w, h, ppd, points, false);
        const std::vector<double> dy = bruteForceFeature(luminance, w, h, ppd, points, true);
        const std::vector<float> &separable = points ? p.points : p.edges;
        for (std::size_t i = 0; i < luminance.size(); ++i)
            ASSERT_NEAR(separable[i], std::hypot(dx[i], dy[i]), 2e-5) << (points ? "points" : "edges") << " at " << i;
    }
}

TEST(FlipError, MoreNoiseIsMoreVisible) {
    const Framebuffer reference = scene(48, 32);
    const FlipReference flip(reference);
    const double small = flip.meanError(noisy(reference, 0.02f, 3));
    const double medium = flip.meanError(noisy(reference, 0.08f, 3));
    const double large = flip.meanError(noisy(reference, 0.3f, 3));
    EXPECT_GT(small, 0.0);
    EXPECT_LT(small, medium);
    EXPECT_LT(medium, large);
    EXPECT_LE(large, 1.0);
}

TEST(FlipError, AMovedEdgeIsSeenByTheFeatureTerm) {
    // Same colours, edge moved by two pixels: the colour term alone sees only the two columns.
    const int w = 40, h = 20;
    Framebuffer a = flat(w, h, glm::vec3(0.2f)), b = a;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (x >= 20) a.at(x, y) = glm::vec3(0.7f);
            if (x >= 22) b.at(x, y) = glm::vec3(0.7f);
        }
    const std::vector<float> map = FlipReference(a).errorMap(b);
    EXPECT_GT(map[std::size_t(10 * w + 21)], 0.5f); // a pixel that changed from bright to dark
    EXPECT_LT(map[std::size_t(10 * w + 2)], 1e-6f);  // far from the edge nothing changed
}

TEST(FlipError, SizesMustMatch) {
    EXPECT_THROW(FlipReference(Framebuffer(4, 4)).errorMap(Framebuffer(4, 5)), Error);
}
