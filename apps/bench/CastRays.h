#pragma once
/// \file CastRays.h
/// The rays of `mvcl-bench cast`, defined exactly so that another tracer can cast the same ones
/// (docs/benchmarks.md, "Cast mode"):
///
/// - a pinhole camera at `eye` looking at `target`, `up` the world's up, `verticalFovDegrees`
///   the full vertical field of view;
/// - in double: forward f = normalize(target − eye), right r = normalize(f × up),
///   u = r × f, h = tan(fovy / 2), aspect a = W / H;
/// - pixel (x, y), row 0 at the top, through its centre:
///   sx = (2 (x + ½) / W − 1) · h · a, sy = (1 − 2 (y + ½) / H) · h,
///   direction = normalize(f + sx r + sy u), rounded to float once;
/// - origin = eye − the scene's world origin, in double, rounded to float once (the loader
///   re-centres far-away models; for a model near the world origin the rays are world rays);
/// - t over [0, ∞), the distance along the unit direction; rays in pixel order (row by row).

#include <mvcl/tracer/Ray.h>

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace mvcl::bench {

struct CastCamera {
    glm::dvec3 eye{0.0};
    glm::dvec3 target{0.0, 0.0, -1.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double verticalFovDegrees = 40.0;

    /// "EYE,TARGET,UP,FOVY": ten comma-separated numbers. Throws mvcl::Error naming the problem.
    static CastCamera parse(const std::string &text);
    /// The same ten numbers, exact enough to read back (%.17g).
    std::string text() const;
};

/// One ray per pixel centre of a width × height image, in pixel order, for a scene whose
/// scene-space origin is at `worldOrigin`. Throws mvcl::Error for a degenerate camera.
std::vector<Ray> castRays(const CastCamera &camera, int width, int height, const glm::dvec3 &worldOrigin);

} // namespace mvcl::bench
