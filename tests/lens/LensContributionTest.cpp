// LensContribution's checks and ray-type restriction for the false-colour and edge stages, and
// PropertyValues::choiceIndex, which lenses use to map a choice onto an enum.

#include <mvcl/core/Error.h>
#include <mvcl/lens/LensContribution.h>
#include <mvcl/lens/PropertyDecl.h>
#include <mvcl/lens/PropertyValues.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mvcl {
namespace {

TEST(LensContribution, FalseColourNeedsAFiniteIncreasingDepthRange) {
    LensContribution c;
    c.shading.falseColor = FalseColorPolicy{FalseColorMode::Depth, 1.f, 5.f};
    EXPECT_NO_THROW(c.validate());
    c.shading.falseColor->depthFar = 1.f;
    EXPECT_THROW(c.validate(), Error);
    c.shading.falseColor->depthFar = std::numeric_limits<float>::infinity();
    EXPECT_THROW(c.validate(), Error);
}

TEST(LensContribution, EdgeLinesNeedAPositiveWidthAColourAndACreaseAngleUpTo180) {
    LensContribution c;
    c.shading.edges = EdgePolicy{EdgeLineMode::Outlines, {0.f, 0.f, 0.f}, 1.5f, 40.f};
    EXPECT_NO_THROW(c.validate());
    for (const float width : {0.f, -1.f, std::nanf("")}) {
        c.shading.edges->widthPixels = width;
        EXPECT_THROW(c.validate(), Error) << width;
    }
    c.shading.edges->widthPixels = 1.f;
    c.shading.edges->creaseDegrees = 181.f;
    EXPECT_THROW(c.validate(), Error);
    c.shading.edges->creaseDegrees = 40.f;
    c.shading.edges->color = {-1.f, 0.f, 0.f};
    EXPECT_THROW(c.validate(), Error);
}

TEST(LensContribution, FalseColourAndEdgesActOnPrimaryRaysOnly) {
    LensContribution c;
    c.shading.falseColor = FalseColorPolicy{FalseColorMode::Layer};
    c.shading.edges = EdgePolicy{EdgeLineMode::Triangles};
    EXPECT_FALSE(c.isIdentity());
    EXPECT_EQ(c.restrictedTo(rayTypeBit(RayType::Primary)), c);
    EXPECT_TRUE(c.restrictedTo(rayTypeBit(RayType::Shadow)).isIdentity());
    ShadingPolicy shading;
    c.shading.applyTo(shading);
    EXPECT_EQ(shading.falseColor.mode, FalseColorMode::Layer);
    EXPECT_EQ(shading.edges.mode, EdgeLineMode::Triangles);
}

TEST(PropertyValues, ChoiceIndexIsThePositionAmongTheDeclaredChoices) {
    const PropertyTable table{PropertyDecl::choice("caps", "solid", {"none", "solid", "hatched"}, "")};
    for (const auto &[value, index] : {std::pair{"none", 0}, std::pair{"solid", 1}, std::pair{"hatched", 2}}) {
        const std::vector<PropertyValue> values{PropertyValue::choice(value)};
        const PropertyValues read(table, values);
        EXPECT_EQ(read.choiceIndex("caps"), index) << value;
        EXPECT_TRUE(read.unreadNames().empty()); // it counts as a read
    }
    const std::vector<PropertyValue> values{PropertyValue::choice("solid")};
    EXPECT_THROW(PropertyValues(table, values).choiceIndex("mode"), Error);
}

} // namespace
} // namespace mvcl
