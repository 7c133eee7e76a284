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
    uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayCounters &operator+=(const RayCounters &o) {
        primary += o.primary;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        nonFiniteSamples += o.nonFiniteSamples;
        return *this;
    }
};

} // namespace mvcl
