#pragma once
/// \file ViewCoordinates.h
/// The one place where a view's coordinate systems meet:
///
/// - framebuffer pixels (input events; x right, y down, (0, 0) the top-left corner),
/// - normalised image coordinates (lens regions; x right, y down, 0..1 over the view),
/// - world space (cameras in session files and on the command line, in the file's units),
/// - scene space (what the tracer and mvcl::Camera work in: world minus Scene::worldOrigin).

#include <mvcl/core/Export.h>

#include <mvcl/io/LensStackFile.h>
#include <mvcl/view/Camera.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace mvcl {

struct Scene;

class MVCL_EXPORT ViewCoordinates {
public:
    ViewCoordinates() = default;
    /// `viewSize` in framebuffer pixels (each side ≥ 1); `worldOrigin` of the scene shown.
    ViewCoordinates(const glm::ivec2 &viewSize, const glm::dvec3 &worldOrigin);
    ViewCoordinates(const glm::ivec2 &viewSize, const Scene &scene);

    const glm::ivec2 &viewSize() const { return m_viewSize; }
    float aspect() const { return float(m_viewSize.x) / float(m_viewSize.y); }
    const glm::dvec3 &worldOrigin() const { return m_worldOrigin; }

    glm::vec2 normalizedFromPixel(const glm::vec2 &pixel) const;
    glm::vec2 pixelFromNormalized(const glm::vec2 &normalized) const;
    /// A distance in pixels as a normalised offset (x and y differ unless the view is square).
    glm::vec2 normalizedFromPixelOffset(const glm::vec2 &pixels) const;

    // The conversions are done in float, as they always were (files store floats, and a camera
    // read from a file must give the same image as before).
    glm::vec3 sceneFromWorld(const glm::vec3 &world) const;
    glm::vec3 worldFromScene(const glm::vec3 &scene) const;
    /// A file's explicit look-at camera (its sceneCamera must be empty) in scene space.
    Camera cameraFromWorld(const LensStackCamera &world) const;
    /// A camera in scene space as a file's explicit look-at camera.
    LensStackCamera worldFromCamera(const Camera &camera) const;

    /// The primary ray through a framebuffer position (scene space, unit direction).
    Ray rayThroughPixel(const Camera &camera, const glm::vec2 &pixel) const;

private:
    glm::ivec2 m_viewSize{1, 1};
    glm::dvec3 m_worldOrigin{0.0};
};

} // namespace mvcl
