// The conformance suite, run over every lens type the in-tree plugin modules register, plus
// tests that each check rejects a lens that breaks its rule (so none of them passes vacuously).

#include "InTreeLensRegistry.h"
#include "LensConformance.h"
#include "TestLenses.h"

#include <gtest/gtest.h>

#include <cctype>
#include <functional>
#include <string>
#include <vector>

using namespace mvcl;
using namespace mvcl::test;

namespace {

LensSubject registeredSubject(const std::string &type) {
    return {type, [type] { return inTreeLenses().registry.create(type); }};
}

std::vector<LensSubject> registeredSubjects() {
    std::vector<LensSubject> subjects;
    for (const std::string &type : inTreeLenses().registry.lensTypes())
        subjects.push_back(registeredSubject(type));
    return subjects;
}

/// Reproducible per lens type and per check, so a failure can be rerun alone.
Random randomFor(const std::string &type, const std::string &check) {
    return Random(uint32_t(std::hash<std::string>{}(type + "/" + check)));
}

std::string testNameOf(const ::testing::TestParamInfo<std::string> &info) {
    std::string name;
    for (const char c : info.param) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return name;
}

} // namespace

TEST(LensConformanceSetup, FindsTheInTreeLensPlugins) {
    for (const Error &error : inTreeLenses().loadErrors) ADD_FAILURE() << error.what();
    const std::vector<std::string> types = inTreeLenses().registry.lensTypes();
    ASSERT_FALSE(types.empty()) << "no lens plugin found; the conformance suite would test nothing";
    for (const char *required : {"layer", "achromatic", "shadow"})
        EXPECT_TRUE(inTreeLenses().registry.contains(required)) << required;
}

class LensConformance : public ::testing::TestWithParam<std::string> {
protected:
    const std::string &type() const { return GetParam(); }
    LensSubject subject() const { return registeredSubject(type()); }
    Random random(const std::string &check) const { return randomFor(type(), check); }
};

TEST_P(LensConformance, DefaultsBuildACommittedLensThatReadsEveryParameter) {
    EXPECT_TRUE(checkDefaults(type(), subject().create));
}

TEST_P(LensConformance, EveryPropertyRoundTripsThroughItsText) {
    Random random = this->random("round-trip");
    EXPECT_TRUE(checkPropertyRoundTrip(subject().create, random));
}

TEST_P(LensConformance, RejectsUnknownKeysWrongTypesAndOutOfRangeValues) {
    EXPECT_TRUE(checkRejectsBadValues(subject().create));
}

TEST_P(LensConformance, DisabledLensChangesNothing) {
    Random random = this->random("disabled");
    EXPECT_TRUE(checkDisabledChangesNothing(subject().create, random));
}

TEST_P(LensConformance, LensOutsideTheImageChangesNothing) {
    Random random = this->random("outside");
    EXPECT_TRUE(checkOutsideImageChangesNothing(subject().create, random));
}

TEST_P(LensConformance, DeclaredIdempotenceHoldsWhenRendered) {
    Random random = this->random("idempotent");
    EXPECT_TRUE(checkIdempotence(subject().create, random));
}

TEST_P(LensConformance, DeclaredCommutativityHoldsWhenRendered) {
    Random random = this->random("commutes");
    EXPECT_TRUE(checkCommutes(subject(), registeredSubjects(), random));
}

TEST_P(LensConformance, RayTypeMaskIsHonoured) {
    Random random = this->random("rays");
    EXPECT_TRUE(checkRayTypeMask(subject().create, random));
}

TEST_P(LensConformance, CommitsWhileOtherThreadsComposeAndRender) {
    Random random = this->random("threads");
    const ::testing::AssertionResult result = checkThreadSafety(subject().create, random);
    EXPECT_TRUE(result);
    RecordProperty("threads", result.message());
}

TEST_P(LensConformance, ContextAndViewDependenceAreHonoured) {
    Random random = this->random("context");
    EXPECT_TRUE(checkContext(subject().create, random));
}

TEST_P(LensConformance, PropertyTableIsDocumented) {
    EXPECT_TRUE(checkDocumented(subject().create));
}

INSTANTIATE_TEST_SUITE_P(InTree, LensConformance,
                         ::testing::ValuesIn(inTreeLenses().registry.lensTypes()), testNameOf);

// --- The checks themselves: an honest test lens passes all of them, lenses that break one
// rule each fail the check for that rule.

namespace {

template <class LensClass> LensFactory committedFactory() {
    return [] {
        auto lens = std::make_shared<LensClass>();
        lens->commit();
        return std::shared_ptr<Lens>(lens);
    };
}

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
