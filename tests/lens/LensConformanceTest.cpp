// The conformance suite (mvcl/testing/LensConformanceSuite.h), run over every lens type the
// in-tree plugin modules register, plus tests that each check rejects a lens that breaks its
// rule (so none of them passes vacuously).

#include "InTreeLensRegistry.h"
#include "TestLenses.h"

#include <mvcl/testing/LensConformanceSuite.h>

#include <gtest/gtest.h>

#include <cctype>
#include <functional>
#include <string>
#include <vector>

using namespace mvcl;
using namespace mvcl::test;

namespace {

/// Every check of the suite on every in-tree lens type (LensConformance/<type>.<check>), the
/// same registration an out-of-tree plugin's tests and mvcl-lens-conformance use.
const int kInTreeConformanceTests = registerLensConformanceTests(inTreeLenses().registry);

} // namespace

// The test tint lens as a statically linked plugin (StaticTintLens.cpp): the one line a plugin
// author's test binary needs, here giving LensConformance/test-tint.<check>.
MVCL_LENS_CONFORMANCE_TESTS(tint);

TEST(LensConformanceSetup, FindsTheInTreeLensPlugins) {
    for (const Error &error : inTreeLenses().loadErrors) ADD_FAILURE() << error.what();
    const std::vector<std::string> types = inTreeLenses().registry.lensTypes();
    ASSERT_FALSE(types.empty()) << "no lens plugin found; the conformance suite would test nothing";
    for (const char *required : {"layer", "achromatic", "shadow"})
        EXPECT_TRUE(inTreeLenses().registry.contains(required)) << required;
    EXPECT_EQ(kInTreeConformanceTests, int(types.size() * conformanceChecks().size()));
}

// --- The checks themselves: an honest test lens passes all of them, lenses that break one
// rule each fail the check for that rule.

namespace {

/// c' = gain·c + lift: two such maps commute only when they are equal, and applying one twice
/// equals once only for the identity. `Claim` is the algebra it (falsely) declares.
template <bool ClaimsCommutes, bool ClaimsIdempotent> class AffineColorLens : public Lens {
public:
    static const LensInfo &typeInfo() {
        static const LensInfo info{
            "test-affine-color", "Scales and lifts the colour.",
            {PropertyDecl::real("gain", 0.5, 0.25, 0.75, "", "Factor on every channel."),
             PropertyDecl::real("lift", 0.1, 0.05, 0.3, "", "Added to every channel.")},
            kAllRayTypes, LensAlgebra{ClaimsCommutes, ClaimsIdempotent}};
        return info;
    }
    AffineColorLens() : Lens(typeInfo()) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &, const LensContext &) const override {
        LensContribution contribution;
        contribution.color.matrix = glm::mat3(float(properties.real("gain")));
        contribution.color.offset = glm::vec3(float(properties.real("lift")));
        return contribution;
    }
};

/// Declares a parameter it never reads and one without documentation.
class SloppyLens : public Lens {
public:
    static const LensInfo &typeInfo() {
        static const LensInfo info{"test-sloppy", "Declares more than it uses.",
                                   {PropertyDecl::real("amount", 0.5, 0.0, 1.0, "", "Used."),
                                    PropertyDecl::boolean("forgotten", false, "")},
                                   kAllRayTypes, LensAlgebra{}};
        return info;
    }
    SloppyLens() : Lens(typeInfo()) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &, const LensContext &) const override {
        LensContribution contribution;
        contribution.color.matrix = glm::mat3(float(properties.real("amount")));
        return contribution;
    }
};

/// Every spatial property type, and a colour offset that moves with the view-space anchor: it
/// follows the camera, and `DeclaresView` says whether it admits it.
template <bool DeclaresView> class AnchoredTintLens : public Lens {
public:
    static const LensInfo &typeInfo() {
        static const LensInfo info{
            "test-anchored-tint",
            "Offsets the colour by where a view-space anchor lies in the scene.",
            {PropertyDecl::point3("anchor", {0.0, 0.0, -1.0}, PropertySpace::View, "scene units",
                                  "A point in front of the camera."),
             PropertyDecl::vector3("axis", {0.0, 1.0, 0.0}, PropertySpace::World, "", "A direction."),
             PropertyDecl::box3("zone", {{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}}, PropertySpace::World, "scene units",
                                "A box."),
             PropertyDecl::transform("placement", glm::dmat4(1.0), PropertySpace::World, "A placement.")},
            kAllRayTypes, LensAlgebra{}, DeclaresView};
        return info;
    }
    AnchoredTintLens() : Lens(typeInfo()) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &context) const override {
        const glm::vec3 anchor = context.scenePoint(properties.point3("anchor"), PropertySpace::View);
        const glm::vec3 axis = context.sceneVector(properties.vector3("axis"), PropertySpace::World);
        const Bounds3f zone = context.sceneBox(properties.box3("zone"), PropertySpace::World);
        const glm::mat4 placement = context.sceneTransform(properties.transform("placement"), PropertySpace::World);
        LensContribution contribution;
        contribution.color.offset =
            0.01f * (anchor + axis + zone.center() + glm::vec3(placement * glm::vec4(0.f, 0.f, 0.f, 1.f)));
        return contribution;
    }
};

} // namespace

TEST(LensConformanceChecks, SpatialPropertiesAndADeclaredViewPassTheChecks) {
    const LensFactory create = committedFactory<AnchoredTintLens<true>>();
    Random random = randomFor("test-anchored-tint", "honest");
    EXPECT_TRUE(checkDefaults("test-anchored-tint", create));
    EXPECT_TRUE(checkPropertyRoundTrip(create, random));
    EXPECT_TRUE(checkRejectsBadValues(create));
    EXPECT_TRUE(checkOutsideImageChangesNothing(create, random));
    EXPECT_TRUE(checkContext(create, random));
    EXPECT_TRUE(checkDocumented(create));
}

TEST(LensConformanceChecks, UndeclaredViewDependenceIsCaught) {
    Random random = randomFor("test-anchored-tint", "undeclared");
    EXPECT_FALSE(checkContext(committedFactory<AnchoredTintLens<false>>(), random));
}

TEST(LensConformanceChecks, HonestTestLensPassesEveryCheck) {
    const LensSubject tint{"test-tint", committedFactory<TintLens>()};
    Random random = randomFor(tint.name, "honest");
    EXPECT_TRUE(checkDefaults(tint.name, tint.create));
    EXPECT_TRUE(checkPropertyRoundTrip(tint.create, random));
    EXPECT_TRUE(checkRejectsBadValues(tint.create));
    EXPECT_TRUE(checkDisabledChangesNothing(tint.create, random));
    EXPECT_TRUE(checkOutsideImageChangesNothing(tint.create, random));
    EXPECT_TRUE(checkRayTypeMask(tint.create, random));
    EXPECT_TRUE(checkThreadSafety(tint.create, random, 50));
    EXPECT_TRUE(checkContext(tint.create, random));
    EXPECT_TRUE(checkDocumented(tint.create));
}

TEST(LensConformanceChecks, FalseIdempotenceClaimIsCaughtByRendering) {
    Random random = randomFor("affine", "idempotent");
    EXPECT_FALSE(checkIdempotence(committedFactory<AffineColorLens<false, true>>(), random));
}

TEST(LensConformanceChecks, FalseCommutativityClaimIsCaughtByRendering) {
    Random random = randomFor("affine", "commutes");
    const LensSubject liar{"test-affine-color", committedFactory<AffineColorLens<true, false>>()};
    EXPECT_FALSE(checkCommutes(liar, {}, random));
}

TEST(LensConformanceChecks, UnreadAndUndocumentedParametersAreCaught) {
    EXPECT_FALSE(checkDefaults("test-sloppy", committedFactory<SloppyLens>()));
    EXPECT_FALSE(checkDocumented(committedFactory<SloppyLens>()));
}
