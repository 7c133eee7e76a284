#pragma once
/// \file Sphere.h

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

namespace mvcl {

struct Sphere {
    std::string name;
    glm::vec3 center{0.f};
    float radius = 1.f;
    uint32_t material = 0;
    int layer = 0;
};

} // namespace mvcl
