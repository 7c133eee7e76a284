#pragma once
/// \file RayPolicy.h
/// What the tracer does for one pixel, as plain data. Lenses compose into one RayPolicy per
/// distinct overlap set; the integrator reads it and never calls back into a lens.

#include <mvcl/tracer/RayQuery.h>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>

namespace mvcl {

enum class RayType : uint8_t { Primary = 0, Shadow = 1, Reflection = 2, Refraction = 3 };
inline constexpr int kRayTypeCount = 4;

/// Ray-type masks: which ray types a lens (or a constraint) applies to.
constexpr uint8_t rayTypeBit(RayType type) { return uint8_t(1u << unsigned(type)); }
inline constexpr uint8_t kAllRayTypes = 0x0f;

/// Every layer at `opacity` (for ShadingPolicy::layerOpacity).
constexpr std::array<float, kMaxLayers> filledOpacity(float opacity) {
    std::array<float, kMaxLayers> opacities{};
    for (float &o : opacities) o = opacity;
    return opacities;
}

/// What a primary hit shows instead of its lit colour.
enum class FalseColorMode : uint8_t {
    Off,    ///< the lit colour
    Depth,  ///< distance from the camera, from depthNear (dark blue) to depthFar (yellow)
    Normal, ///< the surface normal in world axes as RGB (0.5 + 0.5·N)
    Layer,  ///< one colour per layer id
    Mesh,   ///< one colour per mesh (sphere, plane)
};

struct FalseColorPolicy {
    FalseColorMode mode = FalseColorMode::Off;
    float depthNear = 0.f; ///< world units along the ray from the camera (Depth)
    float depthFar = 1.f;  ///< > depthNear; nearer and farther clamp to the ends

    bool operator==(const FalseColorPolicy &other) const = default;
};

/// Lines drawn over a primary hit's colour.
enum class EdgeLineMode : uint8_t {
    Off,
    Triangles, ///< every triangle's edges (a wireframe over the shading)
    Outlines,  ///< silhouettes, boundaries between meshes and creases sharper than creaseDegrees
};

struct EdgePolicy {
    EdgeLineMode mode = EdgeLineMode::Off;
    glm::vec3 color{0.f};     ///< linear RGB of the lines
    float widthPixels = 1.5f; ///< line width in pixels of the image (> 0)
    float creaseDegrees = 40.f; ///< Outlines: normals further apart than this draw a crease line

    bool operator==(const EdgePolicy &other) const = default;
};

/// How hits are lit.
struct ShadingPolicy {
    bool shadows = true;      ///< trace shadow rays at all
    float shadowStrength = 1; ///< 0 = occluded light passes fully, 1 = fully blocked
    glm::vec3 shadowTint{0.f}; ///< colour an occluded light is multiplied by at full strength
    bool reflections = true;  ///< trace mirror rays
    bool refractions = true;  ///< trace refracted rays
    int maxDepth = 8;         ///< bounces after the primary hit (≥ 0)
    /// Opacity of each layer's surfaces to primary rays, in [0, 1]: below 1 a primary hit's
    /// shading is blended with what the ray sees when it continues through the surface
    /// (alpha·front + (1 − alpha)·behind), so outer layers can be translucent instead of gone.
    /// Shadows, reflections and refractions still see every surface as it is.
    std::array<float, kMaxLayers> layerOpacity = filledOpacity(1.f);
    /// Raises a translucent surface's opacity where it is seen edge-on, so silhouettes stay
    /// readable: alpha + (1 − alpha)·edgeOpacity·(1 − |N·V|), in [0, 1].
    float edgeOpacity = 0.f;
    /// Primary rays pass through this many surfaces and show the next one (depth peeling: 0 =
    /// the first surface, as usual). Needs no layers: it counts surfaces along the ray.
    int peelSurfaces = 0;
    /// The layers peeling passes through (bit i: layer i); a surface of another layer is shown
    /// where the ray meets it, so a peel can open the skin and leave the heart whole.
    uint32_t peelLayers = kAllLayers;
    /// Primary hits show a false colour instead of their lit colour (see FalseColorMode).
    FalseColorPolicy falseColor{};
    /// Lines over primary hits (see EdgeLineMode).
    EdgePolicy edges{};

    bool operator==(const ShadingPolicy &other) const = default;
};

/// Affine colour map applied after shading: c' = matrix·c + offset (linear RGB). Affine maps
/// compose by multiplication, so a stack of colour lenses folds into one.
struct ColorPolicy {
    glm::mat3 matrix{1.f};
    glm::vec3 offset{0.f};
    bool isIdentity() const { return matrix == glm::mat3(1.f) && offset == glm::vec3(0.f); }

    bool operator==(const ColorPolicy &other) const = default;
};

struct RayPolicy {
    /// One visibility query template per ray type (indexed by RayType). The integrator
    /// narrows tMax for shadow rays to the light's distance.
    std::array<RayQuery, kRayTypeCount> visibility{};
    ShadingPolicy shading{};
    ColorPolicy color{};

    RayQuery &query(RayType type) { return visibility[size_t(type)]; }
    const RayQuery &query(RayType type) const { return visibility[size_t(type)]; }

    bool operator==(const RayPolicy &other) const = default;
};

} // namespace mvcl
