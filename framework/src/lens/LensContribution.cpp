#include <mvcl/lens/LensContribution.h>

#include <mvcl/core/Error.h>

#include <glm/matrix.hpp>

#include <cmath>
#include <string>

namespace mvcl {

namespace {
// RayQuery{} and anything equivalent to it: no hit can be excluded.
bool constrainsNothing(const RayQuery &query) {
    return query.tMin <= 0.f && query.tMax == RayQuery{}.tMax && query.layerMask == kAllLayers &&
           query.clipCount() == 0;
}

bool isFinite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool isFinite(const glm::mat3 &m) { return isFinite(m[0]) && isFinite(m[1]) && isFinite(m[2]); }

constexpr const char *kRayTypeNames[kRayTypeCount] = {"primary", "shadow", "reflection", "refraction"};

bool includes(uint8_t rayTypes, RayType type) { return (rayTypes & rayTypeBit(type)) != 0; }
} // namespace

void ShadingOverride::applyTo(ShadingPolicy &shading) const {
    if (shadows) shading.shadows = *shadows;
    if (shadowStrength) shading.shadowStrength = *shadowStrength;
    if (shadowTint) shading.shadowTint = *shadowTint;
    if (reflections) shading.reflections = *reflections;
    if (refractions) shading.refractions = *refractions;
    if (maxDepth) shading.maxDepth = *maxDepth;
    if (layerOpacity) shading.layerOpacity = *layerOpacity;
    if (edgeOpacity) shading.edgeOpacity = *edgeOpacity;
    if (peelSurfaces) shading.peelSurfaces = *peelSurfaces;
    if (peelLayers) shading.peelLayers = *peelLayers;
    if (falseColor) shading.falseColor = *falseColor;
    if (edges) shading.edges = *edges;
}

bool ShadingOverride::isEmpty() const {
    return !shadows && !shadowStrength && !shadowTint && !reflections && !refractions && !maxDepth &&
           !layerOpacity && !edgeOpacity && !peelSurfaces && !peelLayers && !falseColor && !edges;
}

LensContribution LensContribution::restrictedTo(uint8_t rayTypes) const {
    LensContribution restricted = *this;
    for (int type = 0; type < kRayTypeCount; ++type)
        if (!includes(rayTypes, RayType(type))) restricted.visibility[size_t(type)] = RayQuery{};
    if (!includes(rayTypes, RayType::Primary)) {
        restricted.sampleFromScreen = glm::mat3(1.f);
        restricted.shading.layerOpacity.reset(); // the opacity stage acts on primary hits
        restricted.shading.edgeOpacity.reset();
        restricted.shading.peelSurfaces.reset();
        restricted.shading.peelLayers.reset();
        restricted.shading.falseColor.reset();
        restricted.shading.edges.reset();
    }
    if (!includes(rayTypes, RayType::Shadow)) {
        restricted.shading.shadows.reset();
        restricted.shading.shadowStrength.reset();
        restricted.shading.shadowTint.reset();
    }
    if (!includes(rayTypes, RayType::Reflection)) restricted.shading.reflections.reset();
    if (!includes(rayTypes, RayType::Refraction)) restricted.shading.refractions.reset();
    return restricted;
}

bool LensContribution::isIdentity() const {
    if (sampleFromScreen != glm::mat3(1.f) || !shading.isEmpty() || !color.isIdentity())
        return false;
    for (const RayQuery &query : visibility)
        if (!constrainsNothing(query)) return false;
    return true;
}

void LensContribution::validate() const {
    const auto fail = [](const std::string &problem) { throw Error("contribution", problem); };
    if (!isFinite(sampleFromScreen) || sampleFromScreen[0][2] != 0.f || sampleFromScreen[1][2] != 0.f ||
        sampleFromScreen[2][2] != 1.f)
        fail("ray shaping (sampleFromScreen) is not a finite affine map");
    if (!(std::abs(glm::determinant(sampleFromScreen)) > 0.f)) fail("ray shaping (sampleFromScreen) is not invertible");
    for (int type = 0; type < kRayTypeCount; ++type) {
        const RayQuery &q = visibility[size_t(type)];
        const std::string rays = std::string(kRayTypeNames[type]) + " rays: ";
        if (!(q.tMin >= 0.f) || !std::isfinite(q.tMin)) fail(rays + "tMin must be finite and ≥ 0");
        if (!(q.tMax >= q.tMin)) fail(rays + "tMax must be ≥ tMin");
        for (int i = 0; i < q.clipCount(); ++i)
            if (!q.clip(i).isValid())
                fail(rays + "clip volume " + std::to_string(i) +
                     " is not valid (non-finite numbers, a box with min > max, a negative radius or a zero normal)");
    }
    if (shading.shadowStrength && !(*shading.shadowStrength >= 0.f && *shading.shadowStrength <= 1.f))
        fail("shadow strength must lie in [0, 1]");
    if (shading.shadowTint && !(isFinite(*shading.shadowTint) && glm::all(glm::greaterThanEqual(*shading.shadowTint, glm::vec3(0.f)))))
        fail("shadow tint must be finite and ≥ 0");
    if (shading.maxDepth && *shading.maxDepth < 0) fail("maxDepth must be ≥ 0");
    if (shading.layerOpacity)
        for (float opacity : *shading.layerOpacity)
            if (!(opacity >= 0.f && opacity <= 1.f)) fail("layer opacities must lie in [0, 1]");
    if (shading.edgeOpacity && !(*shading.edgeOpacity >= 0.f && *shading.edgeOpacity <= 1.f))
        fail("edge opacity must lie in [0, 1]");
    if (shading.peelSurfaces && !(*shading.peelSurfaces >= 0 && *shading.peelSurfaces < 64))
        fail("peelSurfaces must lie in [0, 63]");
    if (shading.falseColor && !(std::isfinite(shading.falseColor->depthNear) && std::isfinite(shading.falseColor->depthFar) &&
                                shading.falseColor->depthNear < shading.falseColor->depthFar))
        fail("a false colour's depth range must be finite with depthNear < depthFar");
    if (shading.edges) {
        const EdgePolicy &edges = *shading.edges;
        if (!(isFinite(edges.color) && glm::all(glm::greaterThanEqual(edges.color, glm::vec3(0.f)))))
            fail("edge colour must be finite and ≥ 0");
        if (!(edges.widthPixels > 0.f && std::isfinite(edges.widthPixels))) fail("edge width must be finite and > 0");
        if (!(edges.creaseDegrees >= 0.f && edges.creaseDegrees <= 180.f))
            fail("crease angle must lie in [0, 180] degrees");
    }
    if (!isFinite(color.matrix) || !isFinite(color.offset)) fail("the colour map is not finite");
}

} // namespace mvcl
