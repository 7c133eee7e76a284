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

/// v unchanged, but the optimiser no longer knows how it was computed. A product passed through
/// here is rounded before anything adds to it, so it is never fused into an FMA, whatever
/// -ffp-contract says: the watertight test needs a·b − c·d exactly antisymmetric, and every
/// build must compute bit-identical hits. mvcl itself compiles with -ffp-contract=off, but a
/// project compiling its sources or headers may not (GCC's default outside ISO mode is
/// -ffp-contract=fast, which fuses across statements). Emits no instruction.
template <typename T> inline T unfused(T v) {
#if defined(__GNUC__) && defined(__x86_64__)
    __asm__("" : "+x"(v)); // "v is in an SSE register and may have changed"
#elif defined(__GNUC__) && defined(__aarch64__)
    __asm__("" : "+w"(v));
#else
    volatile T opaque = v; // slower, but equally opaque
    v = opaque;
#endif
    return v;
}

/// a·b, rounded on its own (see unfused()).
inline float mulUnfused(float a, float b) { return unfused(a * b); }

} // namespace mvcl
