/// peel — depth peeling under the lens: each primary ray shows the k-th surface it meets instead
/// of the first, whatever layer it belongs to. It needs no layer labels, so it helps where layer
/// inference is wrong or a model has none. The surfaces passed still cast shadows and reflect
/// (only primary rays peel). `layers` chooses what may be peeled: a surface of any other layer
/// is shown where the ray meets it. Algebra: the upper lens's `surface` replaces the one below (shading
/// override), so order matters; the same lens twice is the same.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

using namespace mvcl;

namespace {

const LensInfo kPeelLensInfo{
    .name = "peel",
    .description = "Shows the k-th surface along each camera ray under the lens.",
    .properties = {PropertyDecl::integer("surface", 2, 1, 32, "",
                                         "which surface along the ray is shown (1 = the first, as usual)"),
                   PropertyDecl::layers("layers", kAllLayers,
                                        "the layers peeled away; a surface of another layer stops the peel")},
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = false, .idempotent = true},
};

class PeelLens final : public Lens {
public:
    PeelLens() : Lens(kPeelLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &) const override {
        LensContribution contribution;
        contribution.shading.peelSurfaces = properties.integer("surface") - 1;
        contribution.shading.peelLayers = properties.layers("layers");
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(PeelLens, kPeelLensInfo)
