/// xray — outer layers become translucent under the lens instead of disappearing: a primary ray
/// that hits a selected layer blends that surface's shading (at `opacity`) with what it meets
/// when it goes on through it. `edges` raises the opacity where a surface is seen edge-on
/// (alpha + (1 − alpha)·edges·(1 − |N·V|)), so silhouettes stay readable. Shadows, reflections
/// and refractions still see every surface. Algebra: the upper lens's opacities replace the
/// ones below (shading override), so order matters; the same lens twice is the same.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

using namespace mvcl;

namespace {

const LensInfo kXrayLensInfo{
    .name = "xray",
    .description = "Makes the selected layers translucent under the lens, with readable silhouettes.",
    .properties =
        {
            PropertyDecl::layers("layers", layerBit(0), "layers that become translucent"),
            PropertyDecl::real("opacity", 0.25, 0.0, 1.0, "", "opacity of their surfaces (0 = invisible)"),
            PropertyDecl::real("edges", 0.7, 0.0, 1.0, "",
                               "how much opacity rises where a surface is seen edge-on (0 = none)"),
        },
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = false, .idempotent = true},
};

class XrayLens final : public Lens {
public:
    XrayLens() : Lens(kXrayLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &) const override {
        const uint32_t layers = properties.layers("layers");
        const float translucent = float(properties.real("opacity"));
        std::array<float, kMaxLayers> opacity = filledOpacity(1.f);
        for (int layer = 0; layer < kMaxLayers; ++layer)
            if (layers & layerBit(layer)) opacity[size_t(layer)] = translucent;
        LensContribution contribution;
        contribution.shading.layerOpacity = opacity;
        contribution.shading.edgeOpacity = float(properties.real("edges"));
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(XrayLens, kXrayLensInfo)
