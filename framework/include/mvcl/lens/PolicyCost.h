#pragma once
/// \file PolicyCost.h

#include <cstdint>

namespace mvcl {

/// What the pixels using one PolicyMap entry cost in a render. A feathered pixel counts for
/// each policy it blends, with the rays and time of that policy's samples.
struct PolicyCost {
    uint64_t pixels = 0;
    uint64_t rays = 0;
    double milliseconds = 0.0;
};

} // namespace mvcl
