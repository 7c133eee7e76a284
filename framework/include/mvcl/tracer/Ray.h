#pragma once
/// \file Ray.h

#include <glm/vec3.hpp>

namespace mvcl {

/// A ray o + t·d in scene space. `direction` need not be unit length, but primary rays are
/// generated with unit directions so that t is a distance (the layer lens's d uses this).
struct Ray {
    glm::vec3 origin{0.f};
    glm::vec3 direction{0.f, 0.f, -1.f};
    /// Ray cone (Akenine-Möller et al. 2019) for texture filtering: the footprint's width at the
    /// origin and its growth per unit of distance (radians). 0, 0 = a thin ray (finest level).
    float coneWidth = 0.f;
    float coneSpread = 0.f;

    glm::vec3 at(float t) const { return origin + t * direction; }
};

} // namespace mvcl
