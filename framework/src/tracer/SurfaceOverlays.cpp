#include "SurfaceOverlays.h"

#include <mvcl/model/TriangleMesh.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mvcl::detail {

namespace {

/// sRGB-encoded component → linear: the palettes below are chosen as displayed colours, and
/// the framebuffer holds linear radiance that is encoded again on output.
float linearFromSrgb(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
glm::vec3 linearFromSrgb(const glm::vec3 &c) { return {linearFromSrgb(c.x), linearFromSrgb(c.y), linearFromSrgb(c.z)}; }

/// A perceptually ordered ramp from dark blue through teal and green to yellow (displayed colours).
glm::vec3 depthRamp(float x) {
    static constexpr std::array<glm::vec3, 5> kStops{{{0.267f, 0.005f, 0.329f},
                                                      {0.231f, 0.322f, 0.545f},
                                                      {0.129f, 0.569f, 0.549f},
                                                      {0.369f, 0.788f, 0.384f},
                                                      {0.992f, 0.906f, 0.145f}}};
    const float scaled = std::clamp(x, 0.f, 1.f) * float(kStops.size() - 1);
    const size_t lower = std::min(size_t(scaled), kStops.size() - 2);
    return glm::mix(kStops[lower], kStops[lower + 1], scaled - float(lower));
}

/// Ten colours that stay apart when printed and for most colour-blind readers (displayed colours).
glm::vec3 categoryColor(uint32_t index) {
    static constexpr std::array<glm::vec3, 10> kPalette{{{0.90f, 0.62f, 0.00f},
                                                         {0.34f, 0.71f, 0.91f},
                                                         {0.00f, 0.62f, 0.45f},
                                                         {0.94f, 0.89f, 0.26f},
                                                         {0.00f, 0.45f, 0.70f},
                                                         {0.84f, 0.37f, 0.00f},
                                                         {0.80f, 0.47f, 0.65f},
                                                         {0.60f, 0.60f, 0.60f},
                                                         {0.55f, 0.34f, 0.16f},
                                                         {0.95f, 0.95f, 0.95f}}};
    return kPalette[index % kPalette.size()];
}

/// Distinct colours for any number of meshes: hues a golden angle apart.
glm::vec3 hashedColor(uint32_t index) {
    const float hue = std::fmod(float(index) * 0.618034f, 1.f) * 6.f;
    const float saturation = 0.65f, value = 0.92f;
    const float f = hue - std::floor(hue);
    const float p = value * (1.f - saturation), q = value * (1.f - saturation * f),
                t = value * (1.f - saturation * (1.f - f));
    switch (int(hue) % 6) {
    case 0: return {value, t, p};
    case 1: return {q, value, p};
    case 2: return {p, value, t};
    case 3: return {p, q, value};
    case 4: return {t, p, value};
    default: return {value, p, q};
    }
}

} // namespace

glm::vec3 falseColorAt(const FalseColorPolicy &policy, const Hit &hit, const glm::vec3 &normal, float distance,
                       float facing) {
    // Categories are shaded by how squarely the surface faces the viewer, so shapes stay readable.
    const float shade = 0.55f + 0.45f * std::clamp(facing, 0.f, 1.f);
    switch (policy.mode) {
    case FalseColorMode::Off: break;
    case FalseColorMode::Depth:
        return linearFromSrgb(depthRamp((distance - policy.depthNear) / (policy.depthFar - policy.depthNear)));
    case FalseColorMode::Normal: return linearFromSrgb(glm::clamp(0.5f + 0.5f * normal, 0.f, 1.f));
    case FalseColorMode::Layer: return shade * linearFromSrgb(categoryColor(hit.layer));
    case FalseColorMode::Mesh:
        return shade * linearFromSrgb(hashedColor(hit.geometry * 3u + uint32_t(hit.kind)));
    }
    return glm::vec3(0.f);
}

float triangleEdgeCoverage(const TriangleMesh &mesh, const Hit &hit, float pixelWidth, float widthPixels) {
    if (hit.primitive >= mesh.indices.size() || !(pixelWidth > 0.f)) return 0.f;
    const glm::uvec3 tri = mesh.indices[hit.primitive];
    const glm::vec3 p0 = mesh.positions[tri.x], p1 = mesh.positions[tri.y], p2 = mesh.positions[tri.z];
    const float twiceArea = glm::length(glm::cross(p1 - p0, p2 - p0));
    // The distance to the edge opposite a corner is that corner's barycentric times the height
    // over the edge (twice the area over the edge's length).
    const std::array<float, 3> barycentric{1.f - hit.u - hit.v, hit.u, hit.v};
    const std::array<float, 3> opposite{glm::length(p2 - p1), glm::length(p0 - p2), glm::length(p1 - p0)};
    float nearest = std::numeric_limits<float>::infinity();
    for (int corner = 0; corner < 3; ++corner)
        if (opposite[size_t(corner)] > 0.f)
            nearest = std::min(nearest, barycentric[size_t(corner)] * twiceArea / opposite[size_t(corner)]);
    // Half the line on each side of the edge, with a one-pixel ramp for anti-aliasing.
    return std::clamp(0.5f * widthPixels - nearest / pixelWidth + 0.5f, 0.f, 1.f);
}

glm::vec3 hatched(const glm::vec3 &color, const glm::vec3 &position, float period) {
    if (!(period > 0.f)) return color;
    const float along = (position.x + position.y + position.z) / period;
    return along - std::floor(along) < 0.35f ? 0.25f * color : color;
}

} // namespace mvcl::detail
