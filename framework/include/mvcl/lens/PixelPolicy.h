#pragma once
/// \file PixelPolicy.h
/// Everything the renderer needs for the pixels of one overlap set: the tracer's RayPolicy,
/// the primary-ray shaping, and which lenses made it (for cost accounting).

#include <mvcl/tracer/RayPolicy.h>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace mvcl {

struct PixelPolicy {
    RayPolicy ray;
    /// Normalised screen position (0..1, y down) → position the primary ray goes through.
    glm::mat3 sampleFromScreen{1.f};
    /// Bit i set: lens i of the stack (bottom = 0) is part of this policy.
    uint64_t lensSet = 0;

    bool isShaped() const { return sampleFromScreen != glm::mat3(1.f); }
    /// True when pixels on either policy render the same radiance: the same ray policy and
    /// ray shaping. lensSet is not compared; it only says whom the cost is charged to.
    bool rendersLike(const PixelPolicy &other) const {
        return ray == other.ray && sampleFromScreen == other.sampleFromScreen;
    }
    /// Where the primary ray of the image point `pixel` (pixel coordinates, e.g. x + 0.5) of a
    /// width × height image goes through, after ray shaping.
    glm::vec2 samplePosition(const glm::vec2 &pixel, int width, int height) const {
        if (!isShaped()) return pixel;
        const glm::vec3 s = sampleFromScreen * glm::vec3(pixel.x / float(width), pixel.y / float(height), 1.f);
        return {s.x * float(width), s.y * float(height)};
    }
};

} // namespace mvcl
