#include <mvcl/lens/LensContribution.h>

namespace mvcl {

namespace {
// RayQuery{} and anything equivalent to it: no hit can be excluded.
bool constrainsNothing(const RayQuery &query) {
    return query.tMin <= 0.f && query.tMax == RayQuery{}.tMax && query.layerMask == kAllLayers &&
           query.clipCount == 0;
}

bool includes(uint8_t rayTypes, RayType type) { return (rayTypes & rayTypeBit(type)) != 0; }
} // namespace

void ShadingOverride::applyTo(ShadingPolicy &shading) const {
    if (shadows) shading.shadows = *shadows;
    if (shadowStrength) shading.shadowStrength = *shadowStrength;
    if (shadowTint) shading.shadowTint = *shadowTint;
    if (reflections) shading.reflections = *reflections;
    if (refractions) shading.refractions = *refractions;
    if (maxDepth) shading.maxDepth = *maxDepth;
}

bool ShadingOverride::isEmpty() const {
    return !shadows && !shadowStrength && !shadowTint && !reflections && !refractions && !maxDepth;
}

LensContribution LensContribution::restrictedTo(uint8_t rayTypes) const {
    LensContribution restricted = *this;
    for (int type = 0; type < kRayTypeCount; ++type)
        if (!includes(rayTypes, RayType(type))) restricted.visibility[size_t(type)] = RayQuery{};
    if (!includes(rayTypes, RayType::Primary)) restricted.sampleFromScreen = glm::mat3(1.f);
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

} // namespace mvcl
