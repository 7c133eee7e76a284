#pragma once
/// \file RenderStats.h

#include <mvcl/tracer/RayCounters.h>

#include <cstdint>

namespace mvcl {

struct RenderStats {
    double renderMilliseconds = 0.0;
    int threads = 0;
    uint64_t pixels = 0;
    uint64_t samples = 0;
    RayCounters rays;
    double raysPerSecond() const {
        return renderMilliseconds > 0.0 ? double(rays.total()) / (renderMilliseconds * 1e-3) : 0.0;
    }
};

} // namespace mvcl
