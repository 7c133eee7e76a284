#include <mvcl/view/Camera.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace mvcl {

Camera::Camera() { update(); }

Camera Camera::lookAt(const glm::vec3 &eye, const glm::vec3 &target, const glm::vec3 &up,
                      float verticalFovDegrees) {
    Camera c;
    c.m_eye = eye;
    c.m_target = target;
    c.m_up = up;
    c.m_verticalFovDegrees = verticalFovDegrees;
    c.update();
    return c;
}

Camera Camera::fromDesc(const CameraDesc &desc) {
    return lookAt(desc.eye, desc.target, desc.up, desc.verticalFovDegrees);
}

Camera Camera::framing(const Bounds3f &bounds, float verticalFovDegrees, float aspect) {
    return framing(bounds, verticalFovDegrees, aspect, glm::vec3(0.55f, 0.45f, 1.f), glm::vec3(0.f, 1.f, 0.f));
}

Camera Camera::framing(const Bounds3f &bounds, float verticalFovDegrees, float aspect, const glm::vec3 &towardEye,
                       const glm::vec3 &up) {
    if (bounds.isEmpty()) return lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, verticalFovDegrees);
    const glm::vec3 center = bounds.center();
    const glm::vec3 toEye = glm::length(towardEye) > 0.f ? glm::normalize(towardEye) : glm::vec3(0.f, 0.f, 1.f);
    // Orient first at unit distance, then back off until every box corner is inside both the
    // vertical and the horizontal field of view (tighter than the bounding sphere for long models).
    const Camera oriented = lookAt(center + toEye, center, up, verticalFovDegrees);
    const glm::mat3 &axes = oriented.sceneFromCamera(); // right, up, backward
    const float tanV = oriented.m_tanHalfFov;
    const float tanH = tanV * aspect;
    float distance = 0.f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 c = corner - center;
        const float x = std::abs(glm::dot(c, axes[0]));
        const float y = std::abs(glm::dot(c, axes[1]));
        const float towardEye = glm::dot(c, axes[2]);
        distance = std::max({distance, towardEye + x / tanH, towardEye + y / tanV});
    }
    distance = std::max(distance * 1.08f, 1e-30f);
    return lookAt(center + distance * toEye, center, up, verticalFovDegrees);
}

void Camera::update() {
    glm::vec3 forward = m_target - m_eye;
    if (!(glm::length(forward) > 0.f)) forward = {0.f, 0.f, -1.f};
    forward = glm::normalize(forward);
    glm::vec3 right = glm::cross(forward, m_up);
    if (!(glm::length(right) > 1e-6f)) // up parallel to the view: pick any perpendicular
        right = glm::cross(forward, std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    right = glm::normalize(right);
    const glm::vec3 trueUp = glm::cross(right, forward);
    m_sceneFromCamera = glm::mat3(right, trueUp, -forward);
    m_tanHalfFov = std::tan(glm::radians(std::clamp(m_verticalFovDegrees, 1e-3f, 179.f)) * 0.5f);
}

} // namespace mvcl
