/// magnifier — enlarges what lies under the lens about the lens's centre (ray shaping).
///
/// Property table: docs/lenses.md (mvcl-render --list-lenses).
///
/// A pixel at normalised position p shoots its primary ray through c + (p − c)/m, c the region's
/// centre. Algebra: two magnifiers multiply (not idempotent), and a magnifier moves what the
/// lenses above it see (not commutative).

#include <mvcl/lens/LensPlugin.h>

using namespace mvcl;

namespace {

const LensInfo kMagnifierLensInfo{
    .name = "magnifier",
    .description = "Enlarges the image under the lens about its centre.",
    .properties = {PropertyDecl::real("magnification", 2.0, 1.0, 64.0, "",
                                      "how much the lens enlarges the image")},
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = false, .idempotent = false},
};

class MagnifierLens final : public Lens {
public:
    MagnifierLens() : Lens(kMagnifierLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &region, const LensContext &) const override {
        const float scale = float(1.0 / properties.real("magnification"));
        const glm::vec2 center = region.center();
        LensContribution contribution;
        // Homogeneous 2D affine map, glm column-major: p' = scale·p + (1 − scale)·center.
        contribution.sampleFromScreen = glm::mat3(glm::vec3(scale, 0.f, 0.f), glm::vec3(0.f, scale, 0.f),
                                                  glm::vec3((1.f - scale) * center, 1.f));
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(MagnifierLens, kMagnifierLensInfo)
