/// shadow — Bier's drop-shadow lens in 3D: shadows under it shown, removed or tinted, and which
/// layers cast them.
///
/// Property table: docs/lenses.md (mvcl-render --list-lenses).
///
/// In mode `on` occluded light is black (tint 0,0,0) scaled by `strength`. Casters narrow what
/// shadow rays hit (constraints intersect); to let layers hidden by a layer lens cast shadows,
/// give that layer lens rays=primary. Algebra: the upper lens overrides the shading fields it
/// sets, so order matters (not commutative); the same lens twice is the same (idempotent).

#include <mvcl/lens/LensPlugin.h>

using namespace mvcl;

namespace {

const LensInfo kShadowLensInfo{
    .name = "shadow",
    .description = "Shows, removes or tints the shadows under the lens and chooses which layers cast them.",
    .properties =
        {
            PropertyDecl::choice("mode", "on", {"on", "off", "tinted"},
                                 "shadows under the lens: as usual, none, or tinted"),
            PropertyDecl::layers("casters", kAllLayers, "layers that cast shadows under the lens"),
            PropertyDecl::real("strength", 1.0, 0.0, 1.0, "", "how much an occluder blocks light (0 = none)"),
            PropertyDecl::color("tint", glm::vec3(0.3f, 0.3f, 0.5f), "colour of occluded light in mode tinted"),
        },
    .defaultRayTypes = rayTypeBit(RayType::Shadow),
    .algebra = {.commutes = false, .idempotent = true},
};

class ShadowLens final : public Lens {
public:
    ShadowLens() : Lens(kShadowLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &, const LensContext &) const override {
        const std::string &mode = properties.choice("mode");
        LensContribution contribution;
        contribution.visibility[size_t(RayType::Shadow)].layerMask = properties.layers("casters");
        contribution.shading.shadows = mode != "off";
        contribution.shading.shadowStrength = float(properties.real("strength"));
        const glm::vec3 tint = properties.color("tint"); // read in every mode: all parameters are used
        contribution.shading.shadowTint = mode == "tinted" ? tint : glm::vec3(0.f);
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(ShadowLens, kShadowLensInfo)
