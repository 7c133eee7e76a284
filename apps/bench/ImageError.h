#pragma once
/// \file ImageError.h
/// Error of a rendered image against a reference, for `mvcl-bench convergence`. Both images are
/// linear RGB of the same size; every mean is over pixels and the three channels.

#include <mvcl/view/Framebuffer.h>

namespace mvcl::bench {

/// √(mean (I − R)²) on the linear values as rendered (no clamping).
double rootMeanSquaredError(const Framebuffer &image, const Framebuffer &reference);

/// mean (I − R)² / (R² + ε): the relative MSE of the rendering literature. ε keeps dark pixels
/// from dominating (0.01 is the customary choice for images whose bright parts are near 1).
double relativeMeanSquaredError(const Framebuffer &image, const Framebuffer &reference,
                                double epsilon = 0.01);

/// 10 log₁₀(1 / MSE) with peak 1, both images clamped to [0, 1] first (what a display shows);
/// +∞ when the clamped images are equal.
double peakSignalToNoiseRatio(const Framebuffer &image, const Framebuffer &reference);

/// How far apart two images are as 8-bit sRGB files show them: every linear value encoded and
/// rounded to 0..255 as writeImage() does, so two files read back with readImage() compare
/// level for level. For `mvcl-bench image-diff`, which checks that another renderer's picture
/// of the same scene matches ours.
struct LevelDifference {
    double mean = 0.0;        ///< mean |a − b| in levels, over pixels and the three channels
    int max = 0;              ///< the largest |a − b| of any channel of any pixel
    double shareAbove = 0.0;  ///< fraction of pixels with some channel more than `threshold` apart
    int threshold = 0;
};
LevelDifference levelDifference(const Framebuffer &image, const Framebuffer &reference, int threshold = 8);

/// Throws mvcl::Error when the sizes differ (the metrics above call it).
void requireSameSize(const Framebuffer &image, const Framebuffer &reference);

} // namespace mvcl::bench
