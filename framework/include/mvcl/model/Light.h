#pragma once
/// \file Light.h
/// Point and directional lights. The paper's distance term D of eq. 1 is
/// D = constantAttenuation + linearAttenuation·r + quadraticAttenuation·r²  (point lights only).

#include <glm/vec3.hpp>

#include <string>

namespace mvcl {

enum class LightType { Point, Directional };

struct Light {
    std::string name;
    LightType type = LightType::Point;
    /// Point lights: position in scene space.
    glm::vec3 position{0.f};
    /// Directional lights: the direction the light travels (from the light into the scene), unit.
    glm::vec3 direction{0.f, -1.f, 0.f};
    /// I: radiant intensity, linear RGB (colour × strength).
    glm::vec3 intensity{1.f};
    float constantAttenuation = 1.f;
    float linearAttenuation = 0.f;
    float quadraticAttenuation = 0.f;
};

} // namespace mvcl
