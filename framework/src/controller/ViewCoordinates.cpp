#include <mvcl/controller/ViewCoordinates.h>

#include <mvcl/model/Scene.h>

#include <algorithm>

namespace mvcl {

ViewCoordinates::ViewCoordinates(const glm::ivec2 &viewSize, const glm::dvec3 &worldOrigin)
    : m_viewSize(std::max(viewSize.x, 1), std::max(viewSize.y, 1)), m_worldOrigin(worldOrigin) {}

ViewCoordinates::ViewCoordinates(const glm::ivec2 &viewSize, const Scene &scene)
    : ViewCoordinates(viewSize, scene.worldOrigin) {}

glm::vec2 ViewCoordinates::normalizedFromPixel(const glm::vec2 &pixel) const {
    return pixel / glm::vec2(m_viewSize);
}

glm::vec2 ViewCoordinates::pixelFromNormalized(const glm::vec2 &normalized) const {
    return normalized * glm::vec2(m_viewSize);
}

glm::vec2 ViewCoordinates::normalizedFromPixelOffset(const glm::vec2 &pixels) const {
    return pixels / glm::vec2(m_viewSize);
}

glm::vec3 ViewCoordinates::sceneFromWorld(const glm::vec3 &world) const { return world - glm::vec3(m_worldOrigin); }

glm::vec3 ViewCoordinates::worldFromScene(const glm::vec3 &scene) const { return scene + glm::vec3(m_worldOrigin); }

Camera ViewCoordinates::cameraFromWorld(const LensStackCamera &world) const {
    return Camera::lookAt(sceneFromWorld(world.eye), sceneFromWorld(world.target), world.up,
                          world.verticalFovDegrees);
}

LensStackCamera ViewCoordinates::worldFromCamera(const Camera &camera) const {
    return LensStackCamera{"", worldFromScene(camera.eye()), worldFromScene(camera.target()), camera.up(),
                           camera.verticalFovDegrees()};
}

Ray ViewCoordinates::rayThroughPixel(const Camera &camera, const glm::vec2 &pixel) const {
    return camera.generateRay(pixel.x, pixel.y, m_viewSize.x, m_viewSize.y);
}

} // namespace mvcl
