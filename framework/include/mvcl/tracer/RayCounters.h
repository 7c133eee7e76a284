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
    uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayCounters &operator+=(const RayCounters &o) {
        primary += o.primary;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        return *this;
    }
};

} // namespace mvcl
