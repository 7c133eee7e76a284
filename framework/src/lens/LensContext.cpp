#include <mvcl/lens/LensContext.h>

#include <mvcl/model/Scene.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mvcl {

const char *propertySpaceName(PropertySpace space) {
    switch (space) {
    case PropertySpace::World: return "world";
    case PropertySpace::View: return "view";
    case PropertySpace::Bounds: return "bounds";
    }
    return "world";
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

namespace {
// The bounds' lower corner and extent; a unit box at the origin when no scene is known, so that
// bounds space is then the scene space itself.
glm::dvec3 boundsLower(const Bounds3f &bounds) { return bounds.isEmpty() ? glm::dvec3(0.0) : glm::dvec3(bounds.min); }
glm::dvec3 boundsExtent(const Bounds3f &bounds) {
    return bounds.isEmpty() ? glm::dvec3(1.0) : glm::max(glm::dvec3(bounds.extent()), glm::dvec3(1e-30));
}
double largestSide(const Bounds3f &bounds) {
    const glm::dvec3 e = boundsExtent(bounds);
    return std::max(e.x, std::max(e.y, e.z));
}
} // namespace

glm::vec3 LensContext::scenePoint(const glm::dvec3 &point, PropertySpace space) const {
    // View space keeps its float maths (images made before must not change).
    if (space == PropertySpace::View) return camera.eye + sceneFromViewRotation() * glm::vec3(point);
    return glm::vec3(scenePointInDouble(point, space));
}

glm::dvec3 LensContext::scenePointInDouble(const glm::dvec3 &point, PropertySpace space) const {
    switch (space) {
    case PropertySpace::World: return point - worldOrigin;
    case PropertySpace::Bounds: return boundsLower(sceneBounds) + point * boundsExtent(sceneBounds);
    case PropertySpace::View: break;
    }
    return glm::dvec3(scenePoint(point, space));
}

glm::vec3 LensContext::sceneVector(const glm::dvec3 &vector, PropertySpace space) const {
    switch (space) {
    case PropertySpace::World: return glm::vec3(vector);
    case PropertySpace::Bounds: return glm::vec3(vector * (1.0 / boundsExtent(sceneBounds)));
    case PropertySpace::View: break;
    }
    return sceneFromViewRotation() * glm::vec3(vector);
}

double LensContext::sceneLength(double length, PropertySpace space) const {
    return space == PropertySpace::Bounds ? length * largestSide(sceneBounds) : length;
}

glm::dvec3 LensContext::propertyPoint(const glm::dvec3 &scene, PropertySpace space) const {
    switch (space) {
    case PropertySpace::World: return scene + worldOrigin;
    case PropertySpace::Bounds: return (scene - boundsLower(sceneBounds)) / boundsExtent(sceneBounds);
    case PropertySpace::View: break;
    }
    return glm::transpose(glm::dmat3(sceneFromViewRotation())) * (scene - glm::dvec3(camera.eye));
}

glm::dvec3 LensContext::propertyVector(const glm::dvec3 &scene, PropertySpace space) const {
    switch (space) {
    case PropertySpace::World: return scene;
    case PropertySpace::Bounds: return scene * boundsExtent(sceneBounds);
    case PropertySpace::View: break;
    }
    return glm::transpose(glm::dmat3(sceneFromViewRotation())) * scene;
}

double LensContext::propertyLength(double scene, PropertySpace space) const {
    return space == PropertySpace::Bounds ? scene / largestSide(sceneBounds) : scene;
}

Box3d LensContext::propertyBox(const glm::dvec3 &sceneMin, const glm::dvec3 &sceneMax, PropertySpace space) const {
    Box3d box{glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p = propertyPoint({(i & 1) ? sceneMax.x : sceneMin.x, (i & 2) ? sceneMax.y : sceneMin.y,
                                            (i & 4) ? sceneMax.z : sceneMin.z},
                                           space);
        box.min = glm::min(box.min, p);
        box.max = glm::max(box.max, p);
    }
    return box;
}

LensContext::OrientedBox LensContext::sceneOrientedBox(const Box3d &box, const glm::dmat4 &rotation,
                                                       PropertySpace space) const {
    OrientedBox oriented;
    // World and bounds space keep the axes' directions, so the corners map onto corners (in
    // double: the values go back into properties); view space turns the box.
    glm::dvec3 lo = scenePointInDouble(box.min, space), hi = scenePointInDouble(box.max, space);
    if (space == PropertySpace::View) {
        const Bounds3f aligned = sceneBox(box, space);
        lo = glm::dvec3(aligned.min), hi = glm::dvec3(aligned.max);
    }
    oriented.center = 0.5 * (lo + hi);
    oriented.halfExtent = 0.5 * (hi - lo);
    // Gram-Schmidt on the linear part's columns: the nearest rotation for the small shears that
    // rounding leaves, and the identity for the identity.
    glm::dvec3 x = glm::dvec3(rotation[0]), y = glm::dvec3(rotation[1]);
    const double xLength = glm::length(x);
    if (!(xLength > 0.0)) return oriented;
    x /= xLength;
    y -= glm::dot(y, x) * x;
    const double yLength = glm::length(y);
    if (!(yLength > 0.0)) return oriented;
    y /= yLength;
    // A box is its own mirror image, so a mirroring linear part turns it as the rotation does.
    oriented.axes = glm::dmat3(x, y, glm::cross(x, y));
    return oriented;
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
    } else if (space == PropertySpace::Bounds) {
        const glm::dvec3 extent = boundsExtent(sceneBounds);
        for (int c = 0; c < 3; ++c) sceneFromSpace[c][c] = extent[c];
        sceneFromSpace[3] = glm::dvec4(boundsLower(sceneBounds), 1.0);
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
