#pragma once
/// \file FloatBits.h
/// Floating-point helpers for error bounds (pbrt-v4 §6.8 style): gamma(n), next float up/down.

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mvcl {

inline constexpr float kMachineEpsilon = std::numeric_limits<float>::epsilon() * 0.5f;

/// Bound on the relative error of n chained float operations: n·ε / (1 − n·ε).
constexpr float gamma(int n) {
    return (float(n) * kMachineEpsilon) / (1.f - float(n) * kMachineEpsilon);
}

/// The smallest float greater than v (v itself for +inf and NaN).
inline float nextFloatUp(float v) {
    if (std::isinf(v) && v > 0.f) return v;
    if (v == -0.f) v = 0.f;
    uint32_t bits = std::bit_cast<uint32_t>(v);
    bits = v >= 0.f ? bits + 1 : bits - 1;
    return std::bit_cast<float>(bits);
}

/// The largest float smaller than v (v itself for -inf and NaN).
inline float nextFloatDown(float v) {
    if (std::isinf(v) && v < 0.f) return v;
    if (v == 0.f) v = -0.f;
    uint32_t bits = std::bit_cast<uint32_t>(v);
    bits = v > 0.f ? bits - 1 : bits + 1;
    return std::bit_cast<float>(bits);
}

} // namespace mvcl
