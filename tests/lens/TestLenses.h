#pragma once
// A lens defined by the tests themselves: a non-grey colour map, which no in-tree plugin has,
// for order-effect tests and as an honest reference lens for the conformance checks. It is a
// complete lens in a dozen lines, like a plugin would be.

#include <mvcl/lens/Lens.h>

#include <glm/mat3x3.hpp>

#include <memory>

namespace mvcl::test {

/// Multiplies the colour under it per channel. Diagonal maps commute with each other but not
/// with luminance (achromatic), so it declares no algebra.
class TintLens : public Lens {
public:
    static const LensInfo &typeInfo() {
        static const LensInfo info{
            "test-tint", "Multiplies the colour by a tint.",
            {PropertyDecl::color("tint", {1.f, 0.5f, 0.25f}, "Factor per linear RGB channel.")},
            kAllRayTypes, LensAlgebra{}};
        return info;
    }
    TintLens() : Lens(typeInfo()) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &, const LensContext &) const override {
        LensContribution contribution;
        const glm::vec3 tint = properties.color("tint");
        contribution.color.matrix = glm::mat3(tint.x, 0.f, 0.f, 0.f, tint.y, 0.f, 0.f, 0.f, tint.z);
        return contribution;
    }
};

/// A committed lens of test type `LensClass` with `region`.
template <class LensClass> std::shared_ptr<Lens> makeTestLens(const LensRegion &region) {
    auto lens = std::make_shared<LensClass>();
    lens->setRegion(region);
    lens->commit();
    return lens;
}

} // namespace mvcl::test
