#pragma once
/// \file LensContribution.h
/// What one lens asks of the pixels under it, as plain data, one part per stage of a pixel's
/// rendering: ray shaping, visibility, shading, colour.
/// The lens stack folds contributions onto the base policy (see PolicyComposition.h); the
/// renderer never calls into a lens.

#include <mvcl/core/Export.h>

#include <mvcl/tracer/RayPolicy.h>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <optional>

namespace mvcl {

/// Shading fields a lens sets; unset fields leave what lies below. Upper lenses override.
struct MVCL_EXPORT ShadingOverride {
    std::optional<bool> shadows;
    std::optional<float> shadowStrength;
    std::optional<glm::vec3> shadowTint;
    std::optional<bool> reflections;
    std::optional<bool> refractions;
    std::optional<int> maxDepth;
    /// The opacity stage (primary rays): see ShadingPolicy::layerOpacity and edgeOpacity.
    std::optional<std::array<float, kMaxLayers>> layerOpacity;
    std::optional<float> edgeOpacity;
    std::optional<int> peelSurfaces; ///< see ShadingPolicy::peelSurfaces (primary rays)
    std::optional<uint32_t> peelLayers; ///< see ShadingPolicy::peelLayers (primary rays)
    std::optional<FalseColorPolicy> falseColor; ///< see ShadingPolicy::falseColor (primary rays)
    std::optional<EdgePolicy> edges;            ///< see ShadingPolicy::edges (primary rays)

    void applyTo(ShadingPolicy &shading) const;
    bool isEmpty() const;
    bool operator==(const ShadingOverride &other) const = default;
};

struct MVCL_EXPORT LensContribution {
    /// Ray shaping: maps the pixel's normalised screen position (x right, y down, 0..1) to the
    /// position its primary ray is shot through, as a 2D affine map in homogeneous form.
    /// Identity = no shaping. A magnifier scales about the lens centre.
    glm::mat3 sampleFromScreen{1.f};
    /// Visibility constraint per ray type (indexed by RayType). RayQuery{} — all layers,
    /// [0, ∞), no clip volumes — constrains nothing. For primary rays t is the distance from
    /// the camera; for secondary rays it is measured from the spawning hit.
    std::array<RayQuery, kRayTypeCount> visibility{};
    ShadingOverride shading;
    /// Colour after shading; the stack composes colour maps bottom → top.
    ColorPolicy color;

    /// Drops everything that concerns ray types outside `rayTypes`: their visibility, the
    /// shading switches of their rays, and ray shaping unless primary rays are included.
    /// The colour stage acts on the pixel and always stays.
    LensContribution restrictedTo(uint8_t rayTypes) const;
    /// True when applying it changes no policy.
    bool isIdentity() const;
    bool operator==(const LensContribution &other) const = default;
    /// Throws mvcl::Error("contribution", problem) unless every number is finite, ray shaping is
    /// an invertible affine map, every t-range has 0 ≤ tMin ≤ tMax, every clip volume is valid
    /// (ClipVolume::isValid), shadow strength, layer opacities and edge opacity lie in [0, 1], the
    /// tint is ≥ 0 and maxDepth ≥ 0.
    /// Lens::commit() calls it, so that a bad contribution is an error at commit, never on the
    /// render path.
    void validate() const;
};

} // namespace mvcl
