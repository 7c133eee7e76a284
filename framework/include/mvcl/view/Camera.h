#pragma once
/// \file Camera.h
/// Pinhole camera: look-at, vertical field of view. Generates unit-direction primary rays, so
/// t along a primary ray is the distance from the eye (the layer lens's d relies on this).

#include <mvcl/core/Export.h>

#include <mvcl/core/Bounds3.h>
#include <mvcl/model/CameraDesc.h>
#include <mvcl/tracer/Ray.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <span>

namespace mvcl {

class MVCL_EXPORT Camera {
public:
    Camera();
    /// \param eye, target, up scene space; up need not be orthogonal to the view direction
    /// \param verticalFovDegrees in (0, 180)
    static Camera lookAt(const glm::vec3 &eye, const glm::vec3 &target, const glm::vec3 &up,
                         float verticalFovDegrees);
    static Camera fromDesc(const CameraDesc &desc);
    /// A camera that sees all of `bounds` from the front-right-above, at the given aspect ratio.
    static Camera framing(const Bounds3f &bounds, float verticalFovDegrees, float aspect);
    /// The same from the direction `toEye` (from the bounds' centre toward the eye, any length)
    /// with `up`: the front, top or current view direction of an interactive view.
    static Camera framing(const Bounds3f &bounds, float verticalFovDegrees, float aspect,
                          const glm::vec3 &toEye, const glm::vec3 &up);

    const glm::vec3 &eye() const { return m_eye; }
    const glm::vec3 &target() const { return m_target; }
    const glm::vec3 &up() const { return m_up; }
    float verticalFovDegrees() const { return m_verticalFovDegrees; }

    /// Ray through continuous raster position (x, y), (0,0) = top-left corner of the image.
    Ray generateRay(float x, float y, int width, int height) const {
        const float aspect = float(width) / float(height);
        const float sx = (2.f * x / float(width) - 1.f) * m_tanHalfFov * aspect;
        const float sy = (1.f - 2.f * y / float(height)) * m_tanHalfFov;
        const glm::vec3 dir = m_sceneFromCamera * glm::vec3(sx, sy, -1.f);
        Ray ray{m_eye, glm::normalize(dir)};
        // One pixel's angle: what a texture lookup at distance t must cover (ray cones).
        ray.coneSpread = 2.f * m_tanHalfFov / float(height);
        return ray;
    }
    /// generateRay() for each raster position: the same rays bit for bit, four at a time where
    /// the CPU has SIMD (a block's camera rays showed in the frame's profile). `rays` holds at
    /// least as many rays as there are positions.
    void generateRays(std::span<const glm::vec2> positions, int width, int height, std::span<Ray> rays) const;

    /// Continuous raster positions [x0, x1] × [y0, y1] (x1 < x0 when none).
    struct RasterRect {
        float x0, y0, x1, y1;
    };
    /// Where the rays of a width × height image (generateRay()) can meet `box`: a ray through a
    /// raster position outside the rectangle misses the box. Conservative: the box's corners
    /// projected in double, and a margin of two pixels on every side that covers the rounding
    /// of generateRay(). No rectangle (every ray may meet the box) where part of the box lies
    /// behind or beside the eye, whose projection is unbounded; an empty one for an empty box.
    std::optional<RasterRect> rasterFootprint(const Bounds3f &box, int width, int height) const;

    /// Columns: right, up, backward (−forward) in scene space, i.e. the rotation from camera
    /// space to scene space (the camera lives in scene space, like the tracer).
    const glm::mat3 &sceneFromCamera() const { return m_sceneFromCamera; }

    /// Same eye, target, up and field of view (the rest is derived from them).
    bool operator==(const Camera &other) const = default;

private:
    void update();

    glm::vec3 m_eye{0.f, 0.f, 5.f};
    glm::vec3 m_target{0.f};
    glm::vec3 m_up{0.f, 1.f, 0.f};
    float m_verticalFovDegrees = 45.f;
    glm::mat3 m_sceneFromCamera{1.f};
    float m_tanHalfFov = 0.f;
};

} // namespace mvcl
