/// section — a cross-section facing the viewer: under the lens, everything nearer to the camera
/// than `depth` is cut away by a plane perpendicular to the view direction, and where that plane
/// passes through a closed mesh the cut face is drawn in the mesh's colour (solid or hatched),
/// lit as if the cut were real. `thickness` > 0 also cuts away what lies beyond depth +
/// thickness, leaving a slab. depth is a fraction (0..1) of the scene's extent along the view
/// direction, so the default cuts through the middle of any model; the plane turns with the
/// camera. Algebra: visibility constraints intersect, so the lens commutes and is idempotent.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

#include <glm/geometric.hpp>


using namespace mvcl;

namespace {

const LensInfo kSectionLensInfo{
    .name = "section",
    .description = "Cuts the model with a plane facing the viewer and caps the cut solids.",
    .properties =
        {
            PropertyDecl::real("depth", 0.5, 0.0, 1.0, "",
                               "where the plane lies: 0 = the scene's nearest point, 1 = its farthest"),
            PropertyDecl::real("thickness", 0.0, 0.0, 1.0, "", "slab thickness, same units (0 = no back plane)"),
            PropertyDecl::choice("caps", "hatched", {"none", "solid", "hatched"}, "how cut solids are drawn"),
        },
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = true, .idempotent = true},
    .dependsOnView = true, // the plane faces the camera
};

class SectionLens final : public Lens {
public:
    SectionLens() : Lens(kSectionLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &context) const override {
        const auto caps = ClipVolume::CapStyle(properties.choiceIndex("caps")); // declared in enum order
        const double depth = properties.real("depth"), thickness = properties.real("thickness");
        LensContribution contribution;
        if (context.sceneBounds.isEmpty()) return contribution;
        // The scene's extent along the view direction: its box's corners projected on it.
        const glm::vec3 forward = glm::normalize(context.camera.target - context.camera.eye);
        const glm::vec3 center = context.sceneBounds.center(), half = 0.5f * context.sceneBounds.extent();
        const float reach = glm::dot(glm::abs(forward), half), middle = glm::dot(forward, center);
        const float front = middle - reach + float(2.0 * depth) * reach;
        ClipVolume nearSide = ClipVolume::halfSpace(-forward, -front, ClipVolume::Keep::Outside);
        nearSide.setCapStyle(caps);
        for (RayQuery &query : contribution.visibility) query.addClip(nearSide); // "rays" chooses
        if (thickness > 0.0) {
            ClipVolume farSide = ClipVolume::halfSpace(forward, front + float(2.0 * thickness) * reach,
                                                       ClipVolume::Keep::Outside);
            farSide.setCapStyle(caps);
            for (RayQuery &query : contribution.visibility) query.addClip(farSide);
        }
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(SectionLens, kSectionLensInfo)
