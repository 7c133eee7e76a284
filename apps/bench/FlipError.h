#pragma once
/// \file FlipError.h
/// LDR-FLIP, the perceptual difference of Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström
/// and Fairchild (2020), "FLIP: A Difference Evaluator for Alternating Images" (HPG 2020):
/// per pixel a value in [0, 1] for how visible the difference is when the two images are
/// flipped back and forth, for an observer at a given number of pixels per degree.
///
/// Colour: both images in YCxCz, filtered with the achromatic, red-green and blue-yellow
/// contrast sensitivity functions, clamped to the RGB cube, to L*a*b* with the Hunt adjustment,
/// HyAB distance, raised to q_c = 0.7 and redistributed to [0, 1] (p_c = 0.4, p_t = 0.95 of the
/// green-blue distance). Features: edges and points of the normalised luminance (first and
/// second derivatives of a Gaussian whose peak-to-trough width is 0.082°), their difference
/// scaled by 1/√2 and raised to q_f = 0.5. FLIP = ΔE_c^(1 − ΔE_f).
///
/// The images are linear RGB; values are clamped to [0, 1] (the paper's sRGB input, decoded).

#include <mvcl/view/Framebuffer.h>

#include <numbers>
#include <vector>

namespace mvcl::bench {

/// The paper's default observer: a 0.7 m wide 3840-pixel monitor seen from 0.7 m (≈ 67 px/°).
inline constexpr double kFlipDefaultPixelsPerDegree = 0.7 * 3840.0 / 0.7 * std::numbers::pi / 180.0;

/// The reference's half of the computation, done once; then any number of test images.
class FlipReference {
public:
    explicit FlipReference(const Framebuffer &reference,
                           double pixelsPerDegree = kFlipDefaultPixelsPerDegree);

    /// Per-pixel FLIP, row-major. Throws mvcl::Error when the size differs from the reference's.
    std::vector<float> errorMap(const Framebuffer &test) const;
    /// The mean of errorMap: the usual one-number FLIP.
    double meanError(const Framebuffer &test) const;

    /// What both images go through before they are compared (public for tests).
    struct Prepared {
        std::vector<float> lab[3]; ///< filtered, Hunt-adjusted L*, a*, b*
        std::vector<float> edges;  ///< |∇| of the edge detector on the normalised luminance
        std::vector<float> points; ///< |·| of the point detector
    };
    Prepared prepare(const Framebuffer &image) const;

private:
    int m_width;
    int m_height;
    double m_pixelsPerDegree;
    Prepared m_reference;
};

/// One-off FLIP of `test` against `reference` (mean over pixels).
double flipError(const Framebuffer &test, const Framebuffer &reference,
                 double pixelsPerDegree = kFlipDefaultPixelsPerDegree);

} // namespace mvcl::bench
