/// invert — a colour lens written outside the mvcl tree: the image under it becomes its negative.
///
/// Its property table is printed by `mvcl-render --list-lenses` from the declarations below.
///
/// Colour map c' = (1 − 2a)·c + a: a blend between c and 1 − c. Two inverts do not cancel unless
/// both have amount 1, and an invert does not commute with other colour maps.

#include <mvcl/lens/LensPlugin.h>

using namespace mvcl;

namespace {

const LensInfo kInvertLensInfo{
    .name = "invert",
    .description = "Shows the negative of the colours under the lens.",
    .properties = {PropertyDecl::real("amount", 1.0, 0.0, 1.0, "", "0 = unchanged, 1 = negative")},
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = false, .idempotent = false},
};

class InvertLens final : public Lens {
public:
    InvertLens() : Lens(kInvertLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &) const override {
        const float amount = float(properties.real("amount"));
        LensContribution contribution;
        contribution.color.matrix = (1.f - 2.f * amount) * glm::mat3(1.f);
        contribution.color.offset = glm::vec3(amount);
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(InvertLens, kInvertLensInfo)
