// Values between keyframes by declared type: reals, integers, points, vectors and boxes move
// linearly, colours in linear light, choices, booleans, sets and transforms step; the ends are
// the keyframes' values exactly and results stay in the declared range.

#include <mvcl/lens/PropertyInterpolation.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/model/LayerTable.h>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace mvcl;

TEST(PropertyInterpolation, EasingsAreLinearOrSmoothStepAndClampTheFraction) {
    EXPECT_DOUBLE_EQ(eased(Easing::Linear, 0.25), 0.25);
    EXPECT_DOUBLE_EQ(eased(Easing::SmoothStep, 0.25), 0.15625); // 3s² − 2s³
    EXPECT_DOUBLE_EQ(eased(Easing::SmoothStep, 0.5), 0.5);
    EXPECT_DOUBLE_EQ(eased(Easing::SmoothStep, 0.75), 0.84375);
    EXPECT_DOUBLE_EQ(eased(Easing::Linear, -1.0), 0.0);
    EXPECT_DOUBLE_EQ(eased(Easing::SmoothStep, 2.0), 1.0);
    EXPECT_EQ(easingNamed("smooth"), Easing::SmoothStep);
    EXPECT_EQ(easingNamed(easingName(Easing::Linear)), Easing::Linear);
    EXPECT_FALSE(easingNamed("cubic"));
}

TEST(PropertyInterpolation, RealsMoveLinearlyAndStayInRange) {
    const PropertyDecl decl = PropertyDecl::real("amount", 0.5, 0.0, 1.0, "", "a real");
    const PropertyValue from = PropertyValue::real(0.2), to = PropertyValue::real(0.6);
    EXPECT_DOUBLE_EQ(interpolateProperty(decl, from, to, 0.25).toReal(), 0.2 + 0.4 * 0.25);
    EXPECT_EQ(interpolateProperty(decl, from, to, 0.0), from);
    EXPECT_EQ(interpolateProperty(decl, from, to, 1.0), to);
    // An overshooting fraction (never made by the easings, but a caller's) is held in range.
    EXPECT_DOUBLE_EQ(interpolateProperty(decl, from, PropertyValue::real(1.0), 1.5).toReal(), 1.0);
    EXPECT_DOUBLE_EQ(interpolateProperty(decl, PropertyValue::real(0.0), PropertyValue::real(1.0), 0.9999).toReal(),
                     0.9999);
}

TEST(PropertyInterpolation, IntegersRoundToTheNearest) {
    const PropertyDecl decl = PropertyDecl::integer("surface", 2, 1, 32, "", "an integer");
    const PropertyValue from = PropertyValue::integer(1), to = PropertyValue::integer(4);
    EXPECT_EQ(interpolateProperty(decl, from, to, 0.1).toInt(), 1);
    EXPECT_EQ(interpolateProperty(decl, from, to, 0.5).toInt(), 3); // 2.5 rounds away from zero
    EXPECT_EQ(interpolateProperty(decl, from, to, 0.9).toInt(), 4);
}

TEST(PropertyInterpolation, ColoursBlendInLinearLight) {
    const PropertyDecl decl = PropertyDecl::color("tint", glm::vec3(0.f), "a colour");
    const PropertyValue black = PropertyValue::color(glm::vec3(0.f)), white = PropertyValue::color(glm::vec3(1.f));
    // Half way between black and white in linear light is 0.5 linear (sRGB ~188), not the
    // sRGB midpoint 128 (0.214 linear), which a blend of the encoded values would give.
    const glm::vec3 middle = interpolateProperty(decl, black, white, 0.5).toColor();
    EXPECT_FLOAT_EQ(middle.r, 0.5f);
    EXPECT_FLOAT_EQ(middle.g, 0.5f);
    const glm::vec3 mixed = interpolateProperty(decl, PropertyValue::color({1.f, 0.f, 0.f}),
                                                PropertyValue::color({0.f, 0.f, 1.f}), 0.25)
                                .toColor();
    EXPECT_FLOAT_EQ(mixed.r, 0.75f);
    EXPECT_FLOAT_EQ(mixed.g, 0.f);
    EXPECT_FLOAT_EQ(mixed.b, 0.25f);
}

TEST(PropertyInterpolation, PointsVectorsAndBoxesMoveComponentByComponent) {
    const PropertyDecl point = PropertyDecl::point3("center", {0, 0, 0}, PropertySpace::World, "", "a point");
    const glm::dvec3 p = interpolateProperty(point, PropertyValue::point3({0, 0, 0}), PropertyValue::point3({2, -4, 8}),
                                             0.5)
                             .toPoint3();
    EXPECT_EQ(p, glm::dvec3(1, -2, 4));
    const PropertyDecl vector = PropertyDecl::vector3("normal", {1, 0, 0}, PropertySpace::World, "", "a vector");
    EXPECT_EQ(interpolateProperty(vector, PropertyValue::vector3({1, 0, 0}), PropertyValue::vector3({0, 1, 0}), 0.25)
                  .toVector3(),
              glm::dvec3(0.75, 0.25, 0));
    const PropertyDecl box = PropertyDecl::box3("box", {{0, 0, 0}, {1, 1, 1}}, PropertySpace::World, "", "a box");
    const Box3d b = interpolateProperty(box, PropertyValue::box3({{0, 0, 0}, {1, 1, 1}}),
                                        PropertyValue::box3({{2, 2, 2}, {5, 5, 5}}), 0.5)
                        .toBox3();
    EXPECT_EQ(b.min, glm::dvec3(1));
    EXPECT_EQ(b.max, glm::dvec3(3));
}

TEST(PropertyInterpolation, ChoicesBooleansSetsAndTransformsStep) {
    const PropertyDecl choice = PropertyDecl::choice("mode", "on", {"on", "off", "tinted"}, "a choice");
    const PropertyValue on = PropertyValue::choice("on"), tinted = PropertyValue::choice("tinted");
    EXPECT_EQ(interpolateProperty(choice, on, tinted, 0.99), on);
    EXPECT_EQ(interpolateProperty(choice, on, tinted, 1.0), tinted);
    const PropertyDecl flag = PropertyDecl::boolean("flag", false, "a switch");
    EXPECT_FALSE(interpolateProperty(flag, PropertyValue::boolean(false), PropertyValue::boolean(true), 0.5).toBool());
    const PropertyDecl layers = PropertyDecl::layers("layers", kAllLayers, "a layer set");
    EXPECT_EQ(interpolateProperty(layers, PropertyValue::layerSet(1), PropertyValue::layerSet(6), 0.7).toLayerSet(), 1u);
    const PropertyDecl rays = PropertyDecl::rayTypes("rays", 1, "ray types");
    EXPECT_EQ(interpolateProperty(rays, PropertyValue::rayTypeSet(1), PropertyValue::rayTypeSet(3), 1.0).toRayTypeSet(),
              3);
    const PropertyDecl transform = PropertyDecl::transform("frame", glm::dmat4(1.0), PropertySpace::World, "a map");
    const PropertyValue identity = PropertyValue::transform(glm::dmat4(1.0));
    const PropertyValue turned = PropertyValue::transform(glm::rotate(glm::dmat4(1.0), 3.0, glm::dvec3(0, 0, 1)));
    EXPECT_EQ(interpolateProperty(transform, identity, turned, 0.5), identity);
    for (PropertyType type : {PropertyType::Bool, PropertyType::Choice, PropertyType::LayerSet,
                              PropertyType::RayTypeSet, PropertyType::Transform})
        EXPECT_FALSE(interpolatesContinuously(type)) << propertyTypeName(type);
}

TEST(PropertyInterpolation, ValuesOfAnotherTypeAreAnError) {
    const PropertyDecl decl = PropertyDecl::real("distance", 0.0, 0.0, 10.0, "", "a real");
    const std::string message = test::errorOf(
        [&] { interpolateProperty(decl, PropertyValue::real(0.0), PropertyValue::integer(2), 0.5); });
    EXPECT_NE(message.find("distance"), std::string::npos) << message;
}
