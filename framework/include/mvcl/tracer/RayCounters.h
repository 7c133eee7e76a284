#pragma once
/// \file RayCounters.h

#include <cstdint>

namespace mvcl {

/// Ray counts of one render, per ray type; summed across threads by the renderer.
struct RayCounters {
    uint64_t primary = 0;
    uint64_t shadow = 0;
    uint64_t reflection = 0;
    uint64_t refraction = 0;
    /// Samples whose radiance came out NaN or ±∞ and were replaced by black (not rays; not in
    /// total()). Robustness tests require 0: the replacement would otherwise hide the bug.
    uint64_t nonFiniteSamples = 0;

    // Work left out because the policy did not need it (IntegratorPlan); all zero when every
    // stage is forced. Not rays traced, so not in total().

    /// Shadow rays that forcing every stage would have cast toward a light nothing can block.
    uint64_t skippedShadowRays = 0;
    /// Shadow rays answered by one any-hit query where forcing would have walked the occluders
    /// with closest-hit queries (the scene has transparent materials, but none the ray may hit).
    uint64_t skippedTransparentWalks = 0;
    /// Hits at which the reflection/refraction stage was not even considered, because no
    /// material such a ray may hit reflects or refracts under the policy.
    uint64_t skippedSecondaryChecks = 0;
    /// Samples whose colour map was the identity and was not applied.
    uint64_t skippedColorMaps = 0;

    uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayCounters &operator+=(const RayCounters &o) {
        primary += o.primary;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        nonFiniteSamples += o.nonFiniteSamples;
        skippedShadowRays += o.skippedShadowRays;
        skippedTransparentWalks += o.skippedTransparentWalks;
        skippedSecondaryChecks += o.skippedSecondaryChecks;
        skippedColorMaps += o.skippedColorMaps;
        return *this;
    }
};

} // namespace mvcl
