#include <mvcl/lens/LensContext.h>

#include <mvcl/model/Scene.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <cmath>

namespace mvcl {

const char *propertySpaceName(PropertySpace space) {
    return space == PropertySpace::View ? "view" : "world";
}

LensContext LensContext::forScene(const Scene &scene) {
    LensContext context;
    context.sceneBounds = scene.bounds();
    context.worldOrigin = scene.worldOrigin;
    context.layers = scene.layers;
    return context;
}

glm::mat3 LensContext::sceneFromViewRotation() const {
    // The same construction as mvcl::Camera, so that view-space lenses line up with the image.
    glm::vec3 forward = camera.target - camera.eye;
    if (!(glm::length(forward) > 0.f)) forward = {0.f, 0.f, -1.f};
    forward = glm::normalize(forward);
    glm::vec3 right = glm::cross(forward, camera.up);
    if (!(glm::length(right) > 1e-6f))
        right = glm::cross(forward, std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    right = glm::normalize(right);
    return glm::mat3(right, glm::cross(right, forward), -forward);
}

glm::vec3 LensContext::scenePoint(const glm::dvec3 &point, PropertySpace space) const {
    if (space == PropertySpace::World) return sceneFromWorldPoint(point);
    return camera.eye + sceneFromViewRotation() * glm::vec3(point);
}

glm::vec3 LensContext::sceneVector(const glm::dvec3 &vector, PropertySpace space) const {
    if (space == PropertySpace::World) return glm::vec3(vector);
    return sceneFromViewRotation() * glm::vec3(vector);
}

Bounds3f LensContext::sceneBox(const Box3d &box, PropertySpace space) const {
    Bounds3f bounds;
    for (int i = 0; i < 8; ++i)
        bounds.expand(scenePoint({(i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                                  (i & 4) ? box.max.z : box.min.z},
                                 space));
    return bounds;
}

glm::mat4 LensContext::sceneTransform(const glm::dmat4 &transform, PropertySpace space) const {
    // scene ← space ← (transform) ← space ← scene
    glm::dmat4 sceneFromSpace(1.0);
    if (space == PropertySpace::World) {
        sceneFromSpace[3] = glm::dvec4(-worldOrigin, 1.0);
    } else {
        const glm::mat3 r = sceneFromViewRotation();
        for (int c = 0; c < 3; ++c) sceneFromSpace[c] = glm::dvec4(glm::dvec3(r[c]), 0.0);
        sceneFromSpace[3] = glm::dvec4(glm::dvec3(camera.eye), 1.0);
    }
    return glm::mat4(sceneFromSpace * transform * glm::inverse(sceneFromSpace));
}

bool LensContext::sameView(const LensContext &other) const {
    return camera.eye == other.camera.eye && camera.target == other.camera.target && camera.up == other.camera.up &&
           camera.verticalFovDegrees == other.camera.verticalFovDegrees && imageWidth == other.imageWidth &&
           imageHeight == other.imageHeight;
}

bool LensContext::sameScene(const LensContext &other) const {
    if (sceneBounds.min != other.sceneBounds.min || sceneBounds.max != other.sceneBounds.max ||
        worldOrigin != other.worldOrigin || layers.count() != other.layers.count())
        return false;
    for (int i = 0; i < layers.count(); ++i) {
        const Layer &a = layers.layers()[size_t(i)];
        const Layer &b = other.layers.layers()[size_t(i)];
        if (a.id != b.id || a.name != b.name || a.color != b.color) return false;
    }
    return true;
}

} // namespace mvcl
