/// edges — lines over the shading under the lens: outlines (silhouettes, boundaries between
/// meshes and creases sharper than `crease`, found by probe rays half a line width around each
/// camera ray) or the edges of every triangle (a wireframe). Widths are in pixels of the image,
/// whatever the distance. Algebra: the upper lens's lines replace the ones below (shading
/// override), so order matters; the same lens twice is the same.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

using namespace mvcl;

namespace {

const LensInfo kEdgesLensInfo{
    .name = "edges",
    .description = "Draws silhouette, boundary and crease lines, or a wireframe, over the shading.",
    .properties =
        {
            PropertyDecl::choice("lines", "outlines", {"triangles", "outlines"},
                                 "outlines (silhouettes, mesh boundaries, creases) or every triangle edge"),
            PropertyDecl::color("color", {0.01f, 0.01f, 0.01f}, "line colour"),
            PropertyDecl::real("width", 1.5, 0.25, 16.0, "px", "line width in pixels"),
            PropertyDecl::real("crease", 40.0, 0.0, 180.0, "degrees",
                               "outlines: normals further apart than this draw a crease line"),
        },
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = false, .idempotent = true},
};

class EdgesLens final : public Lens {
public:
    EdgesLens() : Lens(kEdgesLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &) const override {
        LensContribution contribution;
        contribution.shading.edges = EdgePolicy{
            .mode = EdgeLineMode(properties.choiceIndex("lines") + 1), // after Off
            .color = properties.color("color"),
            .widthPixels = float(properties.real("width")),
            .creaseDegrees = float(properties.real("crease")),
        };
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(EdgesLens, kEdgesLensInfo)
