#pragma once
/// \file CameraDesc.h
/// A camera stored with a scene (a glTF camera node, or a built-in scene's default view).
/// The view module turns it into a mvcl::Camera.

#include <glm/vec3.hpp>

#include <string>

namespace mvcl {

struct CameraDesc {
    std::string name;
    glm::vec3 eye{0.f, 0.f, 5.f}; ///< scene space
    glm::vec3 target{0.f};
    glm::vec3 up{0.f, 1.f, 0.f};
    float verticalFovDegrees = 45.f;
};

} // namespace mvcl
