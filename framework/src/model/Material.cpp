#include <mvcl/model/Material.h>

#include <cmath>

namespace mvcl {

bool Material::mayTransmit() const {
    // "Not ≤ 0" so that a NaN weight counts as one that may be needed.
    if (!(transparency <= 0.f)) return true;
    if (alphaMode != AlphaMode::Blend) return false;
    return metallicRoughness.baseColorTexture.isSet() || !(metallicRoughness.alpha >= 1.f);
}

bool Material::mayCutOut() const {
    if (alphaMode != AlphaMode::Mask) return false;
    return metallicRoughness.baseColorTexture.isSet() || metallicRoughness.alpha < alphaCutoff ||
           !std::isfinite(metallicRoughness.alpha);
}

} // namespace mvcl
