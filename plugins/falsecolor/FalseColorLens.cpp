/// falsecolor — under the lens, each primary hit shows a false colour instead of its lit colour:
/// its distance from the camera (a dark-blue → yellow ramp over [near, far]; far = 0 fits the
/// range to the scene's bounds as seen from the camera, so the lens follows the view), its
/// normal in world axes (0.5 + 0.5·N as RGB), its layer or its mesh (one colour each, shaded by
/// how squarely the surface faces the camera). Lines, translucency and peeling of other lenses
/// still apply. Algebra: the upper lens's mode replaces the one below (shading override), so
/// order matters; the same lens twice is the same.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <limits>

using namespace mvcl;

namespace {

const LensInfo kFalseColorLensInfo{
    .name = "falsecolor",
    .description = "Colours surfaces by depth, normal, layer or mesh under the lens.",
    .properties =
        {
            PropertyDecl::choice("mode", "depth", {"depth", "normal", "layer", "mesh"}, "what the colour shows"),
            PropertyDecl::real("near", 0.0, 0.0, std::numeric_limits<double>::infinity(), "",
                               "depth: the distance shown dark blue (world units)"),
            PropertyDecl::real("far", 0.0, 0.0, std::numeric_limits<double>::infinity(), "",
                               "depth: the distance shown yellow; 0 = fit near and far to the scene"),
        },
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = false, .idempotent = true},
    .dependsOnView = true, // the fitted depth range
};

class FalseColorLens final : public Lens {
public:
    FalseColorLens() : Lens(kFalseColorLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &context) const override {
        FalseColorPolicy falseColor{.mode = FalseColorMode(properties.choiceIndex("mode") + 1)}; // after Off
        falseColor.depthNear = float(properties.real("near"));
        falseColor.depthFar = float(properties.real("far"));
        if (falseColor.depthFar == 0.f && !context.sceneBounds.isEmpty()) {
            // The nearest and farthest points of the bounds from the eye.
            const glm::vec3 eye = context.camera.eye, lo = context.sceneBounds.min, hi = context.sceneBounds.max;
            falseColor.depthNear = glm::distance(eye, glm::clamp(eye, lo, hi));
            falseColor.depthFar = glm::length(glm::max(glm::abs(eye - lo), glm::abs(eye - hi)));
        }
        if (!(falseColor.depthFar > falseColor.depthNear)) falseColor.depthFar = falseColor.depthNear + 1.f;
        LensContribution contribution;
        contribution.shading.falseColor = falseColor;
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(FalseColorLens, kFalseColorLensInfo)
