#pragma once
/// \file RenderStats.h

#include <mvcl/lens/PolicyCost.h>
#include <mvcl/tracer/RayCounters.h>

#include <cstdint>
#include <vector>

namespace mvcl {

struct RenderStats {
    double renderMilliseconds = 0.0;
    int threads = 0;
    uint64_t pixels = 0;
    uint64_t samples = 0;
    RayCounters rays;
    /// Cost of each PolicyMap entry (same index). Milliseconds are summed over threads.
    std::vector<PolicyCost> perPolicy;
    double raysPerSecond() const {
        return renderMilliseconds > 0.0 ? double(rays.total()) / (renderMilliseconds * 1e-3) : 0.0;
    }
};

} // namespace mvcl
