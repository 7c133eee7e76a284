#include <mvcl/controller/CameraNavigation.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace mvcl {

namespace {

/// How close to the up axis an orbit may bring the eye: about 0.06°.
constexpr float kPoleMarginRadians = 1e-3f;

glm::vec3 unitOr(const glm::vec3 &v, const glm::vec3 &fallback) {
    const float length = glm::length(v);
    return length > 0.f && std::isfinite(length) ? v / length : fallback;
}

} // namespace

const char *viewPresetName(ViewPreset preset) {
    switch (preset) {
    case ViewPreset::Front: return "front";
    case ViewPreset::Back: return "back";
    case ViewPreset::Left: return "left";
    case ViewPreset::Right: return "right";
    case ViewPreset::Top: return "top";
    case ViewPreset::Bottom: return "bottom";
    }
    return "?";
}

Camera orbitCamera(const Camera &camera, float yawRadians, float pitchRadians) {
    const glm::vec3 offset = camera.eye() - camera.target();
    const float distance = glm::length(offset);
    if (!(distance > 0.f)) return camera;
    const glm::vec3 up = unitOr(camera.up(), {0.f, 1.f, 0.f});
    const glm::vec3 direction = offset / distance;
    // Polar angle from the up axis; the pitch is clamped so that it stays inside (0, π).
    const float polar = std::acos(std::clamp(glm::dot(direction, up), -1.f, 1.f));
    const float newPolar = std::clamp(polar - pitchRadians, kPoleMarginRadians, glm::pi<float>() - kPoleMarginRadians);
    const glm::vec3 right = camera.sceneFromCamera()[0];
    const glm::quat pitch = glm::angleAxis(newPolar - polar, right); // +angle about right lowers the eye
    const glm::quat yaw = glm::angleAxis(yawRadians, up);
    const glm::vec3 turned = yaw * (pitch * direction);
    // Rotations keep lengths up to rounding; scale back so the distance is kept as exactly as
    // float allows.
    const glm::vec3 eye = camera.target() + distance * unitOr(turned, direction);
    return Camera::lookAt(eye, camera.target(), camera.up(), camera.verticalFovDegrees());
}

Camera panCamera(const Camera &camera, const glm::vec2 &pixelOffset, const glm::ivec2 &viewSize) {
    const float distance = glm::length(camera.eye() - camera.target());
    const float height = float(std::max(viewSize.y, 1));
    // Size of one pixel at the target's depth.
    const float worldPerPixel = 2.f * distance * std::tan(glm::radians(camera.verticalFovDegrees()) * 0.5f) / height;
    const glm::mat3 &axes = camera.sceneFromCamera(); // right, up, backward
    const glm::vec3 move = (-pixelOffset.x * axes[0] + pixelOffset.y * axes[1]) * worldPerPixel;
    return Camera::lookAt(camera.eye() + move, camera.target() + move, camera.up(), camera.verticalFovDegrees());
}

Camera zoomCamera(const Camera &camera, float factor, const glm::vec3 &anchor) {
    if (!(factor > 0.f) || !std::isfinite(factor)) return camera;
    const glm::vec3 eye = anchor + factor * (camera.eye() - anchor);
    const glm::vec3 target = anchor + factor * (camera.target() - anchor);
    // A zoom that would put the eye on the target (factor rounding to nothing) is not a view.
    if (!(glm::length(target - eye) > 0.f)) return camera;
    return Camera::lookAt(eye, target, camera.up(), camera.verticalFovDegrees());
}

Camera framedCamera(const Camera &camera, const Bounds3f &bounds, float aspect) {
    return Camera::framing(bounds, camera.verticalFovDegrees(), aspect, camera.eye() - camera.target(), camera.up());
}

Camera presetCamera(const Camera &camera, ViewPreset preset, const Bounds3f &bounds, float aspect) {
    glm::vec3 toEye{0.f, 0.f, 1.f}, up{0.f, 1.f, 0.f};
    switch (preset) {
    case ViewPreset::Front: break;
    case ViewPreset::Back: toEye = {0.f, 0.f, -1.f}; break;
    case ViewPreset::Left: toEye = {-1.f, 0.f, 0.f}; break;
    case ViewPreset::Right: toEye = {1.f, 0.f, 0.f}; break;
    case ViewPreset::Top: toEye = {0.f, 1.f, 0.f}, up = {0.f, 0.f, -1.f}; break;
    case ViewPreset::Bottom: toEye = {0.f, -1.f, 0.f}, up = {0.f, 0.f, 1.f}; break;
    }
    return Camera::framing(bounds, camera.verticalFovDegrees(), aspect, toEye, up);
}

} // namespace mvcl
