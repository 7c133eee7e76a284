/// section — a cross-section: under the lens, everything on the near side of a plane is cut
/// away, and where that plane passes through a closed mesh the cut face is drawn in the mesh's
/// colour (solid or hatched), lit as if the cut were real. `thickness` > 0 also cuts away what
/// lies beyond the plane + thickness, leaving a slab.
/// - facing=view (the default): the plane faces the viewer and turns with the camera; depth is
///   a fraction (0..1) of the scene's extent along the view direction, so the default cuts
///   through the middle of any model.
/// - facing=plane: the plane is fixed in the model, through planePoint with planeNormal
///   pointing to the side that is cut away (frame=scene: fractions of the scene bounds, as
///   clip's), so a user can grab and turn it.
/// thickness is a fraction of the scene's extent along the plane's normal. `layers` spares the
/// layers left out. Algebra: visibility constraints intersect, so the lens commutes and is
/// idempotent.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

#include <glm/geometric.hpp>

using namespace mvcl;

namespace {

PropertyDecl framed(const PropertyDecl &decl) {
    return decl.withSpaceFrom("frame", {{"scene", PropertySpace::Bounds}, {"world", PropertySpace::World}})
        .whenChoice("facing", "plane");
}

const LensInfo kSectionLensInfo{
    .name = "section",
    .description = "Cuts the model with a plane (facing the viewer, or fixed in the model) and caps the cut solids.",
    .properties =
        {
            PropertyDecl::choice("facing", "view", {"view", "plane"},
                                 "the plane faces the viewer at `depth`, or is fixed through planePoint"),
            PropertyDecl::real("depth", 0.5, 0.0, 1.0, "",
                               "facing view: where the plane lies, 0 = the scene's nearest point, 1 = its farthest")
                .whenChoice("facing", "view"),
            PropertyDecl::real("thickness", 0.0, 0.0, 1.0, "",
                               "slab thickness as a fraction of the scene's extent along the normal (0 = no back plane)"),
            PropertyDecl::choice("frame", "scene", {"scene", "world"},
                                 "plane coordinates as fractions of the scene bounds (0..1 per axis) or in world units"),
            framed(PropertyDecl::point3("planePoint", {0.5, 0.5, 0.5}, PropertySpace::Bounds, "",
                                        "facing plane: a point on the plane")),
            framed(PropertyDecl::vector3("planeNormal", {0.0, 0.0, 1.0}, PropertySpace::Bounds, "",
                                         "facing plane: the normal, pointing to the side cut away")),
            PropertyDecl::choice("caps", "hatched", {"none", "solid", "hatched"}, "how cut solids are drawn"),
            PropertyDecl::layers("layers", kAllLayers, "the layers the section cuts; the others stay whole"),
        },
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = true, .idempotent = true},
    .dependsOnView = true, // facing=view: the plane faces the camera
};

class SectionLens final : public Lens {
public:
    SectionLens() : Lens(kSectionLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &context) const override {
        const auto caps = ClipVolume::CapStyle(properties.choiceIndex("caps")); // declared in enum order
        const double depth = properties.real("depth"), thickness = properties.real("thickness");
        const glm::vec3 planePoint = context.scenePoint(properties.point3("planePoint"), properties.space("planePoint"));
        const glm::vec3 planeNormal =
            context.sceneNormal(properties.vector3("planeNormal"), properties.space("planeNormal"));
        const uint32_t layers = properties.layers("layers");
        const bool facingView = properties.choice("facing") == "view";
        LensContribution contribution;
        if (context.sceneBounds.isEmpty() || (!facingView && !(glm::length(planeNormal) > 0.f))) return contribution;
        // The plane's forward direction points away from the cut side: the view direction, or
        // against the plane's normal.
        const glm::vec3 forward =
            glm::normalize(facingView ? context.camera.target - context.camera.eye : -planeNormal);
        // The scene's extent along it: its box's corners projected on it.
        const glm::vec3 center = context.sceneBounds.center(), half = 0.5f * context.sceneBounds.extent();
        const float reach = glm::dot(glm::abs(forward), half), middle = glm::dot(forward, center);
        const float front = facingView ? middle - reach + float(2.0 * depth) * reach : glm::dot(forward, planePoint);
        const auto add = [&](const ClipVolume &volume) {
            ClipVolume capped = volume;
            capped.setCapStyle(caps);
            capped.setLayerMask(layers);
            for (RayQuery &query : contribution.visibility) query.addClip(capped); // "rays" chooses
        };
        add(ClipVolume::halfSpace(-forward, -front, ClipVolume::Keep::Outside));
        if (thickness > 0.0)
            add(ClipVolume::halfSpace(forward, front + float(2.0 * thickness) * reach, ClipVolume::Keep::Outside));
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(SectionLens, kSectionLensInfo)
