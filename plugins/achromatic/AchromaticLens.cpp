/// achromatic — Bier's achromatic lens: the colour under it is reduced to its luminance.
///
/// Property table: docs/lenses.md (mvcl-render --list-lenses).
///
/// Colour map: (1 − amount)·I + amount·L, where L replaces linear RGB by its Rec. 709 luminance
/// 0.2126 r + 0.7152 g + 0.0722 b in all three channels. All such maps are polynomials in L, so
/// any two achromatic lenses commute; two at amount a are not one at a (not idempotent).

#include <mvcl/lens/LensPlugin.h>

using namespace mvcl;

namespace {

const LensInfo kAchromaticLensInfo{
    .name = "achromatic",
    .description = "Reduces the colour under the lens to its luminance.",
    .properties = {PropertyDecl::real("amount", 1.0, 0.0, 1.0, "",
                                      "how far colour is reduced to grey (0 = unchanged, 1 = grey)")},
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = true, .idempotent = false},
};

class AchromaticLens final : public Lens {
public:
    AchromaticLens() : Lens(kAchromaticLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &, const LensContext &) const override {
        const float amount = float(properties.real("amount"));
        const glm::vec3 luma{0.2126f, 0.7152f, 0.0722f};
        // glm is column-major: column j holds input channel j's weight in every output channel.
        const glm::mat3 toLuminance(glm::vec3(luma.r), glm::vec3(luma.g), glm::vec3(luma.b));
        LensContribution contribution;
        contribution.color.matrix = (1.f - amount) * glm::mat3(1.f) + amount * toLuminance;
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(AchromaticLens, kAchromaticLensInfo)
