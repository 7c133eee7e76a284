#pragma once
/// \file RenderSettings.h

#include <mvcl/tracer/IntegratorPlan.h>

#include <cstdint>

namespace mvcl {

/// How a RenderSession spends samples once a pixel has its first one.
enum class SamplingMode : uint8_t {
    /// Exactly `samplesPerPixel` samples per pixel, then the view is idle (batch renders,
    /// lens-drag frames that must equal a full re-render).
    Fixed,
    /// Every pixel gets more samples, pass after pass, until `maxSamplesPerPixel`, the target
    /// error or the time limit is reached.
    Progressive,
    /// Like Progressive, but after `minSamplesPerPixel` a pixel gets more samples only while its
    /// estimated error (or a neighbour's) is above `targetError`, and the pixels whose next
    /// sample cuts the error most (estimate² / samples) get theirs first.
    Adaptive,
};

struct RenderSettings {
    int width = 800;          ///< pixels, ≥ 1
    int height = 600;         ///< pixels, ≥ 1
    int samplesPerPixel = 4;  ///< Fixed mode: samples per pixel (≥ 1), on a progressive 2-D sequence
    int threads = 0;          ///< 0 = all cores; the image does not depend on it
    int tileSize = 16;        ///< pixels per tile side
    uint32_t seed = 0;        ///< jitter seed; same seed → same image

    SamplingMode sampling = SamplingMode::Fixed;
    int minSamplesPerPixel = 8;     ///< Adaptive: samples before a pixel's error estimate is trusted (≥ 2)
    int maxSamplesPerPixel = 1024;  ///< Progressive/Adaptive: no pixel gets more (≥ 1)
    /// Progressive/Adaptive: stop when every pixel's estimated relative error is at most this
    /// (0 = no error target). The estimate is the standard error of the pixel's mean from two
    /// contiguous blocks of its samples (means A of the first a = 2^m, B of the other b):
    /// Σ_c |A_c − B_c|·√(ab)/n / √(ε + I_r + I_g + I_b), I the mean, ε = 1e-4; from 4 samples
    /// on, each channel's (A_c − B_c)²·ab/n² is at least the same term for the two halves of
    /// the first p samples (p the last power of two below n) times p/n.
    float targetError = 0.f;
    double timeLimitSeconds = 0.0;  ///< stop refining after this long since the last reset (0 = none)
    /// While the camera moves, a reduced-resolution preview sized to take about this long
    /// (seconds; 0 = never preview, always render full resolution).
    double previewBudgetSeconds = 1.0 / 30.0;
    /// Leave out the stages no pixel needs (shadow rays nothing can block, transparent-shadow
    /// walks where no caster is transparent, secondary rays of materials that neither reflect
    /// nor refract, identity colour maps): StageSelection::SkipUnneeded, else ForceAll. The
    /// image is the same either way. Off only to measure what leaving them out saves.
    bool skipUnneededStages = true;
};

/// The integrator's stage selection that `settings` ask for (skipUnneededStages).
inline StageSelection stageSelectionOf(const RenderSettings &settings) {
    return settings.skipUnneededStages ? StageSelection::SkipUnneeded : StageSelection::ForceAll;
}

} // namespace mvcl
