#include <mvcl/lens/PropertyDecl.h>
#include <mvcl/lens/PropertyValues.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/core/Error.h>
#include <mvcl/model/LayerTable.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

using namespace mvcl;
using test::errorOf;

namespace {

void expectRoundTrip(const PropertyDecl &decl, const PropertyValue &value) {
    const std::string text = value.toString();
    EXPECT_EQ(decl.parse(text), value) << decl.name << ": " << text;
}

const PropertyDecl kDistance =
    PropertyDecl::real("distance", 0.0, 0.0, 1.0, "scene units", "how far");
const PropertyDecl kAnyReal = PropertyDecl::real(
    "anything", 0.0, -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), "", "any real");
const PropertyDecl kCount = PropertyDecl::integer("count", 3, -5, 10, "", "how many");
const PropertyDecl kFlag = PropertyDecl::boolean("flag", false, "on or off");
const PropertyDecl kTint = PropertyDecl::color("tint", glm::vec3(1.f), "a colour");
const PropertyDecl kMode =
    PropertyDecl::choice("mode", "on", {"on", "off", "tinted"}, "what to do");
const PropertyDecl kLayers = PropertyDecl::layers("layers", kAllLayers, "which layers");
const PropertyDecl kRays = PropertyDecl::rayTypes("rays", kAllRayTypes, "which rays");

} // namespace

TEST(PropertyValue, TypedAccessRejectsOtherTypes) {
    const PropertyValue real = PropertyValue::real(0.25);
    EXPECT_EQ(real.type(), PropertyType::Real);
    EXPECT_EQ(real.toReal(), 0.25);
    EXPECT_THROW(real.toInt(), Error);
    EXPECT_THROW(real.toBool(), Error);
    EXPECT_THROW(PropertyValue::integer(2).toReal(), Error);
    EXPECT_THROW(PropertyValue::choice("a").toLayerSet(), Error);
    EXPECT_THROW(PropertyValue::layerSet(3).toRayTypeSet(), Error);
    EXPECT_EQ(PropertyValue().type(), PropertyType::Bool);
    EXPECT_FALSE(PropertyValue().toBool());
}

TEST(PropertyValue, EveryTypeRoundTripsThroughItsText) {
    expectRoundTrip(kFlag, PropertyValue::boolean(true));
    expectRoundTrip(kFlag, PropertyValue::boolean(false));
    for (int n : {-5, -1, 0, 7, 10}) expectRoundTrip(kCount, PropertyValue::integer(n));
    for (double x : {0.0, 1.0, 0.1, 1.0 / 3.0, 5e-324, 0.999999999999})
        expectRoundTrip(kDistance, PropertyValue::real(x));
    for (glm::vec3 c : {glm::vec3(0.f), glm::vec3(0.1f, 0.2f, 0.3f), glm::vec3(1e-20f, 7.f, 1e20f)})
        expectRoundTrip(kTint, PropertyValue::color(c));
    for (const char *choice : {"on", "off", "tinted"})
        expectRoundTrip(kMode, PropertyValue::choice(choice));
    for (uint32_t mask : {0u, kAllLayers, layerBit(0), layerBit(31), layersFrom(2), layersFrom(31),
                          0x5555'5555u, 0x8000'0001u, layerBit(0) | layersFrom(5), 0x0000'00e5u})
        expectRoundTrip(kLayers, PropertyValue::layerSet(mask));
    for (uint32_t mask = 0; mask <= kAllRayTypes; ++mask)
        expectRoundTrip(kRays, PropertyValue::rayTypeSet(uint8_t(mask)));
}

TEST(PropertyValue, RandomRealsRoundTripBitExactly) {
    std::mt19937_64 random(12345);
    for (int i = 0; i < 20000; ++i) {
        // Random bit patterns cover every exponent, subnormals included.
        const uint64_t bits = random();
        double x = 0.0;
        std::memcpy(&x, &bits, sizeof x);
        if (!std::isfinite(x)) continue;
        const PropertyValue parsed = kAnyReal.parse(PropertyValue::real(x).toString());
        const double back = parsed.toReal();
        ASSERT_EQ(std::memcmp(&back, &x, sizeof x), 0) << PropertyValue::real(x).toString();
    }
}

TEST(PropertyValue, RandomColoursRoundTripBitExactly) {
    std::mt19937 random(777);
    std::uniform_real_distribution<float> component(0.f, 4.f);
    for (int i = 0; i < 5000; ++i) {
        const glm::vec3 c(component(random), component(random), component(random));
        ASSERT_EQ(kTint.parse(PropertyValue::color(c).toString()).toColor(), c);
    }
}

TEST(PropertyValue, CanonicalTexts) {
    EXPECT_EQ(PropertyValue::boolean(true).toString(), "true");
    EXPECT_EQ(PropertyValue::integer(-42).toString(), "-42");
    EXPECT_EQ(PropertyValue::real(0.1).toString(), "0.1");
    EXPECT_EQ(PropertyValue::real(2.5).toString(), "2.5");
    EXPECT_EQ(PropertyValue::color({0.5f, 1.f, 0.25f}).toString(), "0.5,1,0.25");
    EXPECT_EQ(layerSetToString(kAllLayers), "all");
    EXPECT_EQ(layerSetToString(0), "none");
    EXPECT_EQ(layerSetToString(layersFrom(2)), "2-");
    EXPECT_EQ(layerSetToString(layerBit(0) | layerBit(2) | layerBit(5) | layerBit(6) | layerBit(7)),
              "0,2,5-7");
    EXPECT_EQ(layerSetToString(layerBit(1) | layersFrom(4)), "1,4-");
    EXPECT_EQ(layerSetToString(layerBit(31)), "31");
    EXPECT_EQ(rayTypeSetToString(kAllRayTypes), "all");
    EXPECT_EQ(rayTypeSetToString(0), "none");
    EXPECT_EQ(rayTypeSetToString(rayTypeBit(RayType::Refraction) | rayTypeBit(RayType::Primary)),
              "primary,refraction");
}

TEST(PropertyValue, LayerSetParsing) {
    EXPECT_EQ(parseLayerSet("all"), kAllLayers);
    EXPECT_EQ(parseLayerSet(" None "), 0u);
    EXPECT_EQ(parseLayerSet("3"), layerBit(3));
    EXPECT_EQ(parseLayerSet("0, 2 ,5-7"),
              layerBit(0) | layerBit(2) | layerBit(5) | layerBit(6) | layerBit(7));
    EXPECT_EQ(parseLayerSet("2-"), layersFrom(2));
    EXPECT_EQ(parseLayerSet("0-31"), kAllLayers);
    EXPECT_EQ(parseLayerSet("4-4"), layerBit(4));
    EXPECT_EQ(parseLayerSet("5-7,6"), parseLayerSet("5-7"));
    for (const char *bad : {"", "32", "-1", "1,,2", "7-5", "a", "1-x", "2--3", "1.5", "0x3", "3 4"})
        EXPECT_THROW(parseLayerSet(bad), Error) << bad;
}

TEST(PropertyValue, RayTypeSetParsing) {
    EXPECT_EQ(parseRayTypeSet("all"), kAllRayTypes);
    EXPECT_EQ(parseRayTypeSet("none"), 0);
    EXPECT_EQ(parseRayTypeSet("shadow, primary"),
              rayTypeBit(RayType::Shadow) | rayTypeBit(RayType::Primary));
    EXPECT_EQ(parseRayTypeSet("primary,shadow,reflection,refraction"), kAllRayTypes);
    for (const char *bad : {"", "primary,", "camera", "primary shadow"})
        EXPECT_THROW(parseRayTypeSet(bad), Error) << bad;
}

TEST(PropertyDecl, ParsesLenientSpellingsIntoCanonicalValues) {
    for (const char *yes : {"true", "1", "on", "yes", " TRUE "})
        EXPECT_TRUE(kFlag.parse(yes).toBool()) << yes;
    for (const char *no : {"false", "0", "off", "no"}) EXPECT_FALSE(kFlag.parse(no).toBool()) << no;
    EXPECT_EQ(kTint.parse("[0.5, 0.25, 1]").toColor(), glm::vec3(0.5f, 0.25f, 1.f));
    EXPECT_EQ(kTint.parse("0.5").toColor(), glm::vec3(0.5f));
    EXPECT_EQ(kDistance.parse("  0.5 ").toReal(), 0.5);
    EXPECT_EQ(kDistance.parse("1e-1").toReal(), 0.1);
    EXPECT_EQ(kCount.parse("-5").toInt(), -5);
}

TEST(PropertyDecl, ParseErrorsNameThePropertyAndTheProblem) {
    EXPECT_EQ(errorOf([] { kDistance.parse("abc"); }), "property 'distance': \"abc\" is not a number");
    EXPECT_EQ(errorOf([] { kDistance.parse("2.5"); }),
              "property 'distance': 2.5 is outside [0, 1] scene units");
    EXPECT_EQ(errorOf([] { kMode.parse("foo"); }),
              "property 'mode': \"foo\" is not one of on|off|tinted");
    EXPECT_EQ(errorOf([] { kLayers.parse("1,40"); }), "property 'layers': layer 40 is outside 0..31");
    EXPECT_NE(errorOf([] { kCount.parse("11"); }).find("outside [-5, 10]"), std::string::npos);
    EXPECT_NE(errorOf([] { kFlag.parse("maybe"); }).find("property 'flag'"), std::string::npos);
    EXPECT_NE(errorOf([] { kRays.parse("camera"); }).find("property 'rays'"), std::string::npos);
}

TEST(PropertyDecl, RejectsMalformedNumbers) {
    for (const char *bad : {"", "nan", "inf", "-inf", "1e999", "0.5x", "0.5 0.5", "+", "--1", "0,5"})
        EXPECT_THROW(kAnyReal.parse(bad), Error) << bad;
    for (const char *bad : {"", "1.0", "3x", "1e2", "99999999999", " - 1", "0x1"})
        EXPECT_THROW(kCount.parse(bad), Error) << bad;
    for (const char *bad : {"", "1,2", "1,2,3,4", "[1,2,3", "a,b,c", "nan,0,0", "1,,2", "-1,0,0"})
        EXPECT_THROW(kTint.parse(bad), Error) << bad;
}

TEST(PropertyDecl, ValidateChecksTypeRangeAndChoices) {
    EXPECT_NO_THROW(kDistance.validate(PropertyValue::real(0.0)));
    EXPECT_NO_THROW(kDistance.validate(PropertyValue::real(1.0)));
    EXPECT_THROW(kDistance.validate(PropertyValue::real(-1e-9)), Error);
    EXPECT_THROW(kDistance.validate(PropertyValue::real(std::nan(""))), Error);
    EXPECT_THROW(kAnyReal.validate(PropertyValue::real(INFINITY)), Error);
    EXPECT_THROW(kDistance.validate(PropertyValue::integer(0)), Error);
    EXPECT_THROW(kCount.validate(PropertyValue::integer(-6)), Error);
    EXPECT_THROW(kTint.validate(PropertyValue::color({0.f, -0.1f, 0.f})), Error);
    EXPECT_THROW(kTint.validate(PropertyValue::color({0.f, NAN, 0.f})), Error);
    EXPECT_THROW(kMode.validate(PropertyValue::choice("On")), Error);
    EXPECT_THROW(kRays.validate(PropertyValue::rayTypeSet(0x10)), Error);
    EXPECT_NO_THROW(kLayers.validate(PropertyValue::layerSet(0)));
}

TEST(PropertyDecl, BuildersFillTheDeclaration) {
    EXPECT_EQ(kCount.type, PropertyType::Int);
    EXPECT_EQ(kCount.minimum, -5);
    EXPECT_EQ(kCount.maximum, 10);
    EXPECT_EQ(kCount.defaultValue, PropertyValue::integer(3));
    EXPECT_EQ(kDistance.unit, "scene units");
    EXPECT_EQ(kDistance.doc, "how far");
    EXPECT_EQ(kTint.minimum, 0.0);
    EXPECT_EQ(kMode.choices.size(), 3u);
    EXPECT_EQ(kRays.defaultValue, PropertyValue::rayTypeSet(kAllRayTypes));
}

TEST(PropertyDecl, RangeTexts) {
    EXPECT_EQ(kDistance.rangeText(), "[0, 1] scene units");
    EXPECT_EQ(kCount.rangeText(), "[-5, 10]");
    EXPECT_EQ(kTint.rangeText(), "[0, ∞)");
    EXPECT_EQ(kAnyReal.rangeText(), "(-∞, ∞)");
    EXPECT_EQ(kMode.rangeText(), "one of on|off|tinted");
    EXPECT_FALSE(kLayers.rangeText().empty());
}

TEST(PropertyDecl, FindProperty) {
    const PropertyTable table{kDistance, kMode};
    ASSERT_NE(findProperty(table, "mode"), nullptr);
    EXPECT_EQ(findProperty(table, "mode")->type, PropertyType::Choice);
    EXPECT_EQ(findProperty(table, "Mode"), nullptr);
    EXPECT_EQ(findProperty(table, "rays"), nullptr);
}

TEST(PropertyValues, TypedReadsTrackWhatWasRead) {
    const PropertyTable table{kDistance, kMode, kLayers, kFlag};
    const std::vector<PropertyValue> values{PropertyValue::real(0.75), PropertyValue::choice("off"),
                                            PropertyValue::layerSet(layersFrom(1)),
                                            PropertyValue::boolean(true)};
    const PropertyValues properties(table, values);
    EXPECT_EQ(properties.unreadNames(), (std::vector<std::string>{"distance", "mode", "layers", "flag"}));
    EXPECT_EQ(properties.real("distance"), 0.75);
    EXPECT_EQ(properties.choice("mode"), "off");
    EXPECT_EQ(properties.unreadNames(), (std::vector<std::string>{"layers", "flag"}));
    EXPECT_EQ(properties.layers("layers"), layersFrom(1));
    EXPECT_EQ(properties.value("flag"), PropertyValue::boolean(true));
    EXPECT_TRUE(properties.unreadNames().empty());
}

TEST(PropertyValues, ReadsOfUndeclaredNamesOrWrongTypesThrow) {
    const PropertyTable table{kDistance};
    const std::vector<PropertyValue> values{PropertyValue::real(0.5)};
    const PropertyValues properties(table, values);
    EXPECT_THROW(properties.real("distanse"), Error);
    EXPECT_NE(errorOf([&] { properties.integer("distance"); }).find("property 'distance'"),
              std::string::npos);
    EXPECT_THROW(properties.color("distance"), Error);
    EXPECT_THROW(properties.rayTypes("distance"), Error);
}

// --- the spatial types ---------------------------------------------------------------------------

namespace {
const PropertyDecl kAnchor = PropertyDecl::point3("anchor", {0.0, 0.0, -1.0}, PropertySpace::View, "scene units", "a point");
const PropertyDecl kAxis = PropertyDecl::vector3("axis", {0.0, 1.0, 0.0}, PropertySpace::World, "", "a direction");
const PropertyDecl kZone =
    PropertyDecl::box3("zone", {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}}, PropertySpace::World, "m", "a box");
const PropertyDecl kPlacement = PropertyDecl::transform("placement", glm::dmat4(1.0), PropertySpace::World, "a map");
} // namespace

TEST(PropertyValue, SpatialTypesRoundTripBitExactlyThroughTheirText) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> any(-1e7, 1e7);
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 a{any(rng), any(rng), any(rng)}, b{any(rng), any(rng), any(rng)};
        expectRoundTrip(kAnchor, PropertyValue::point3(a));
        expectRoundTrip(kAxis, PropertyValue::vector3(b));
        expectRoundTrip(kZone, PropertyValue::box3({glm::min(a, b), glm::max(a, b)}));
        glm::dmat4 m(1.0);
        m[0][0] = 1.0 + std::abs(a.x) * 1e-7;
        m[1][2] = b.y * 1e-7;
        m[3] = glm::dvec4(a, 1.0);
        expectRoundTrip(kPlacement, PropertyValue::transform(m));
    }
}

TEST(PropertyValue, SpatialTextsAndAccess) {
    EXPECT_EQ(PropertyValue::point3({1.0, -2.5, 3.0}).toString(), "1,-2.5,3");
    EXPECT_EQ(PropertyValue::box3({{0.0, 1.0, 2.0}, {3.0, 4.0, 5.0}}).toString(), "0,1,2,3,4,5");
    EXPECT_EQ(PropertyValue::transform(glm::dmat4(1.0)).toString(), "1,0,0,0,0,1,0,0,0,0,1,0");
    glm::dmat4 shift(1.0);
    shift[3] = glm::dvec4(4.0, 5.0, 6.0, 1.0);
    EXPECT_EQ(PropertyValue::transform(shift).toString(), "1,0,0,4,0,1,0,5,0,0,1,6") << "rows of [R | t]";
    EXPECT_EQ(kPlacement.parse("identity"), PropertyValue::transform(glm::dmat4(1.0)));
    EXPECT_EQ(kPlacement.parse("[1,0,0,4, 0,1,0,5, 0,0,1,6]").toTransform(), shift);
    EXPECT_EQ(kAnchor.parse(" [1, 2, 3] ").toPoint3(), glm::dvec3(1.0, 2.0, 3.0));
    EXPECT_EQ(kZone.parse("0,0,0,1,2,3").toBox3().max, glm::dvec3(1.0, 2.0, 3.0));
    EXPECT_THROW(PropertyValue::point3({}).toVector3(), Error);
    EXPECT_THROW(PropertyValue::vector3({}).toPoint3(), Error);
    EXPECT_THROW(PropertyValue::box3({}).toTransform(), Error);
    EXPECT_EQ(PropertyValue::box3({}).components().size(), 6u);
    EXPECT_EQ(PropertyValue::transform(glm::dmat4(1.0)).components().size(), 12u);
}

TEST(PropertyDecl, SpatialValuesAreCheckedWithClearErrors) {
    EXPECT_NE(errorOf([] { kZone.parse("1,0,0,0,1,1"); }).find("minimum exceeds its maximum on x"), std::string::npos);
    EXPECT_NE(errorOf([] { kAnchor.parse("1,2"); }).find("is not a point (x,y,z)"), std::string::npos);
    EXPECT_NE(errorOf([] { kAnchor.parse("1,nan,2"); }).find("property 'anchor'"), std::string::npos);
    EXPECT_NE(errorOf([] { kPlacement.parse("0,0,0,0,0,0,0,0,0,0,0,0"); }).find("not invertible"), std::string::npos);
    EXPECT_NE(errorOf([] { kPlacement.parse("1,0,0"); }).find("affine transform"), std::string::npos);
    PropertyDecl bounded = kAxis;
    bounded.minimum = -1.0;
    bounded.maximum = 1.0;
    EXPECT_NE(errorOf([&] { bounded.validate(PropertyValue::vector3({0.0, 2.0, 0.0})); }).find("outside [-1, 1]"),
              std::string::npos);
    EXPECT_NE(errorOf([] { kAxis.validate(PropertyValue::point3({})); }).find("expects a value of type vector3"),
              std::string::npos);
    EXPECT_EQ(kAnchor.rangeText(), "(-∞, ∞) scene units per component, view space");
    EXPECT_EQ(kZone.rangeText(), "(-∞, ∞) m per component, world space");
    EXPECT_EQ(kPlacement.rangeText(), "affine (identity or 12 numbers), world space");
    EXPECT_EQ(kAnchor.space, PropertySpace::View);
}
