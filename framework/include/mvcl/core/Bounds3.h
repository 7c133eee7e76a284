#pragma once
/// \file Bounds3.h
/// Axis-aligned bounding box in single precision.

#include <glm/vec3.hpp>
#include <glm/common.hpp>

#include <limits>

namespace mvcl {

struct Bounds3f {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    bool isEmpty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void expand(const glm::vec3 &p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void expand(const Bounds3f &b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return isEmpty() ? glm::vec3(0.f) : max - min; }
    /// Surface area; 0 for an empty box.
    float area() const {
        const glm::vec3 e = extent();
        return 2.f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
    int longestAxis() const {
        const glm::vec3 e = extent();
        return (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
    }
    bool contains(const glm::vec3 &p) const {
        return p.x >= min.x && p.y >= min.y && p.z >= min.z && p.x <= max.x && p.y <= max.y &&
               p.z <= max.z;
    }
};

} // namespace mvcl
