#pragma once
// Private to the tracer: three floats in the low lanes of one SSE register, for shading arithmetic
// on colours and directions. A sum, difference, product or quotient of two of them is one
// instruction where glm's vec3 takes two or three and shuffles; lane by lane it is the same IEEE
// operation glm does per component, so the results are the same bits. Dot products add their
// three products in glm's order, (x + y) + z. Without SSE2 the same type wraps a glm::vec3.

#include <glm/vec3.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl::detail {

#if defined(__SSE2__)

struct Lanes3 {
    __m128 v; ///< x, y, z and a fourth lane nobody reads

    /// x and y in one 8-byte load, z beside them (_mm_setr_ps built the register from three).
    static Lanes3 of(const glm::vec3 &a) {
        const __m128 xy = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(&a.x)));
        return {_mm_movelh_ps(xy, _mm_load_ss(&a.z))};
    }
    static Lanes3 splat(float s) { return {_mm_set1_ps(s)}; }
    glm::vec3 toVec3() const {
        alignas(16) float lanes[4];
        _mm_store_ps(lanes, v);
        return {lanes[0], lanes[1], lanes[2]};
    }

    friend Lanes3 operator+(Lanes3 a, Lanes3 b) { return {_mm_add_ps(a.v, b.v)}; }
    friend Lanes3 operator-(Lanes3 a, Lanes3 b) { return {_mm_sub_ps(a.v, b.v)}; }
    friend Lanes3 operator*(Lanes3 a, Lanes3 b) { return {_mm_mul_ps(a.v, b.v)}; }
    friend Lanes3 operator/(Lanes3 a, Lanes3 b) { return {_mm_div_ps(a.v, b.v)}; }
};

/// glm::dot: (a.x·b.x + a.y·b.y) + a.z·b.z.
inline float dot(Lanes3 a, Lanes3 b) {
    const __m128 p = _mm_mul_ps(a.v, b.v);
    return (_mm_cvtss_f32(p) + _mm_cvtss_f32(_mm_shuffle_ps(p, p, 1))) + _mm_cvtss_f32(_mm_shuffle_ps(p, p, 2));
}

#else

struct Lanes3 {
    glm::vec3 v;

    static Lanes3 of(const glm::vec3 &a) { return {a}; }
    static Lanes3 splat(float s) { return {glm::vec3(s)}; }
    glm::vec3 toVec3() const { return v; }

    friend Lanes3 operator+(Lanes3 a, Lanes3 b) { return {a.v + b.v}; }
    friend Lanes3 operator-(Lanes3 a, Lanes3 b) { return {a.v - b.v}; }
    friend Lanes3 operator*(Lanes3 a, Lanes3 b) { return {a.v * b.v}; }
    friend Lanes3 operator/(Lanes3 a, Lanes3 b) { return {a.v / b.v}; }
};

inline float dot(Lanes3 a, Lanes3 b) {
    const glm::vec3 p = a.v * b.v;
    return (p.x + p.y) + p.z;
}

#endif

} // namespace mvcl::detail
