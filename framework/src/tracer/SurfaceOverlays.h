#pragma once
// Private to the tracer: what a primary hit shows in place of, or on top of, its lit colour —
// false colours, triangle-edge lines and the stripes of a hatched cap.

#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/RayPolicy.h>

#include <glm/vec3.hpp>

namespace mvcl {

struct TriangleMesh;

namespace detail {

/// The false colour of `policy.mode` (not Off) at `hit`: `normal` is the unit surface normal
/// facing the viewer, `distance` the distance from the camera, `facing` = |N·V| in [0, 1].
glm::vec3 falseColorAt(const FalseColorPolicy &policy, const Hit &hit, const glm::vec3 &normal, float distance,
                       float facing);

/// How much of a line `widthPixels` wide along the triangle's edges covers the hit, 0..1,
/// given the width of one pixel on the surface (`pixelWidth`, scene units).
float triangleEdgeCoverage(const TriangleMesh &mesh, const Hit &hit, float pixelWidth, float widthPixels);

/// A hatched cap's colour at `position`: dark diagonal stripes `period` apart.
glm::vec3 hatched(const glm::vec3 &color, const glm::vec3 &position, float period);

} // namespace detail
} // namespace mvcl
