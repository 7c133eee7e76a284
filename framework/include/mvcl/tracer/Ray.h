#pragma once
/// \file Ray.h

#include <glm/vec3.hpp>

namespace mvcl {

/// A ray o + t·d in scene space. `direction` need not be unit length, but primary rays are
/// generated with unit directions so that t is a distance (the layer lens's d uses this).
struct Ray {
    glm::vec3 origin{0.f};
    glm::vec3 direction{0.f, 0.f, -1.f};

    glm::vec3 at(float t) const { return origin + t * direction; }
};

} // namespace mvcl
