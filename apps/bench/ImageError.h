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

/// Throws mvcl::Error when the sizes differ (the metrics above call it).
void requireSameSize(const Framebuffer &image, const Framebuffer &reference);

} // namespace mvcl::bench
