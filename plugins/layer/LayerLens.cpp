/// layer — the paper's semi-volumetric lens. Inside its region rays see only the selected layers
/// ("from layer k inward" or any set), and primary rays only hits at least `distance` away.
///
/// Property table: docs/lenses.md (mvcl-render --list-lenses).
///
/// With the default `rays` the hidden layers neither show nor cast shadows inside the lens; set
/// rays=primary to keep their shadows. `distance` constrains primary rays only.
/// Algebra: visibility constraints intersect, so the lens commutes and is idempotent.

#include <mvcl/lens/LensPlugin.h>

#include <limits>

using namespace mvcl;

namespace {

const LensInfo kLayerLensInfo{
    .name = "layer",
    .description = "Inside the lens, rays see only the selected layers and only hits beyond a distance.",
    .properties =
        {
            PropertyDecl::layers("layers", layersFrom(1), "layers rays under the lens may hit"),
            PropertyDecl::real("distance", 0.0, 0.0, std::numeric_limits<double>::infinity(),
                               "scene units", "primary hits nearer than this are skipped"),
        },
    .defaultRayTypes = uint8_t(rayTypeBit(RayType::Primary) | rayTypeBit(RayType::Shadow)),
    .algebra = {.commutes = true, .idempotent = true},
};

class LayerLens final : public Lens {
public:
    LayerLens() : Lens(kLayerLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &, const LensContext &) const override {
        LensContribution contribution;
        // Every ray type gets the mask; Lens keeps only the types in "rays".
        for (RayQuery &query : contribution.visibility) query.layerMask = properties.layers("layers");
        contribution.visibility[size_t(RayType::Primary)].tMin = float(properties.real("distance"));
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(LayerLens, kLayerLensInfo)
