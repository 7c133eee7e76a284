// What each in-tree lens plugin (plugins/*) contributes for given properties, read from its
// committed snapshot: the parameter tables in the plugin sources, checked.

#include <mvcl/lens/LensRegistry.h>

#include <gtest/gtest.h>

namespace mvcl {
namespace {

constexpr size_t kPrimary = size_t(RayType::Primary);
constexpr size_t kShadow = size_t(RayType::Shadow);
constexpr size_t kReflection = size_t(RayType::Reflection);

class InTreeLensPluginsTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        registry = new LensRegistry;
        registry->loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / "mvcl-lens-layer.so");
        registry->loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / "mvcl-lens-achromatic.so");
        registry->loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / "mvcl-lens-shadow.so");
        registry->loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / "mvcl-lens-magnifier.so");
    }
    static void TearDownTestSuite() { delete registry; }

    /// A lens of `type` with `properties` (name, text) set and committed.
    static std::shared_ptr<Lens> lens(const std::string &type,
                                      const std::vector<std::pair<std::string, std::string>> &properties = {}) {
        std::shared_ptr<Lens> lens = registry->create(type);
        for (const auto &[name, text] : properties) lens->setPropertyText(name, text);
        lens->commit();
        return lens;
    }
    /// A copy: callers pass a temporary lens, and its snapshot dies with it.
    static LensContribution contribution(const std::shared_ptr<Lens> &lens) {
        return lens->snapshot()->contribution;
    }

    static LensRegistry *registry;
};

LensRegistry *InTreeLensPluginsTest::registry = nullptr;

void expectNear(const glm::vec3 &actual, const glm::vec3 &expected) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-6f) << "component " << i;
}

TEST_F(InTreeLensPluginsTest, LayerLensHidesOuterLayersFromPrimaryAndShadowRaysByDefault) {
    const auto layer = lens("layer");
    const LensContribution &c = contribution(layer);
    EXPECT_EQ(c.visibility[kPrimary].layerMask, layersFrom(1));
    EXPECT_EQ(c.visibility[kShadow].layerMask, layersFrom(1));
    EXPECT_EQ(c.visibility[kReflection].layerMask, kAllLayers) << "not in the default rays";
    EXPECT_EQ(c.visibility[kPrimary].tMin, 0.f);
    EXPECT_TRUE(c.shading.isEmpty());
    EXPECT_TRUE(c.color.isIdentity());
}

TEST_F(InTreeLensPluginsTest, LayerLensDistanceConstrainsPrimaryRaysOnly) {
    const auto layer = lens("layer", {{"layers", "0,2"}, {"distance", "2.5"}});
    const LensContribution &c = contribution(layer);
    EXPECT_EQ(c.visibility[kPrimary].layerMask, layerBit(0) | layerBit(2));
    EXPECT_EQ(c.visibility[kPrimary].tMin, 2.5f);
    EXPECT_EQ(c.visibility[kShadow].layerMask, layerBit(0) | layerBit(2));
    EXPECT_EQ(c.visibility[kShadow].tMin, 0.f);

    const auto keepShadows = lens("layer", {{"rays", "primary"}});
    EXPECT_EQ(contribution(keepShadows).visibility[kShadow].layerMask, kAllLayers);
    EXPECT_THROW(lens("layer", {{"distance", "-1"}}), Error);
}

TEST_F(InTreeLensPluginsTest, AchromaticLensBlendsTowardsRec709Luminance) {
    const glm::vec3 red(1.f, 0.f, 0.f), green(0.f, 1.f, 0.f);
    expectNear(contribution(lens("achromatic")).color.matrix * green, glm::vec3(0.7152f));
    EXPECT_TRUE(contribution(lens("achromatic", {{"amount", "0"}})).color.isIdentity());
    const glm::mat3 half = contribution(lens("achromatic", {{"amount", "0.5"}})).color.matrix;
    expectNear(half * red, glm::vec3(0.5f + 0.5f * 0.2126f, 0.5f * 0.2126f, 0.5f * 0.2126f));
    EXPECT_THROW(lens("achromatic", {{"amount", "1.5"}}), Error);
}

TEST_F(InTreeLensPluginsTest, AchromaticLensAlgebraAsDeclared) {
    const auto achromatic = lens("achromatic");
    EXPECT_TRUE(achromatic->info().algebra.commutes);
    EXPECT_FALSE(achromatic->info().algebra.idempotent);
    const glm::mat3 a = contribution(lens("achromatic", {{"amount", "0.3"}})).color.matrix;
    const glm::mat3 b = contribution(lens("achromatic", {{"amount", "0.8"}})).color.matrix;
    const glm::vec3 colour(0.9f, 0.2f, 0.4f);
    expectNear(a * (b * colour), b * (a * colour));
    const glm::vec3 once = a * colour, twice = a * (a * colour);
    EXPECT_GT(glm::length(twice - once), 1e-3f) << "amount 0.3 twice is greyer than once";
}

TEST_F(InTreeLensPluginsTest, ShadowLensModes) {
    const ShadingOverride on = contribution(lens("shadow")).shading;
    EXPECT_EQ(on.shadows, true);
    EXPECT_EQ(on.shadowStrength, 1.f);
    EXPECT_EQ(on.shadowTint, glm::vec3(0.f));

    EXPECT_EQ(contribution(lens("shadow", {{"mode", "off"}})).shading.shadows, false);

    const ShadingOverride tinted =
        contribution(lens("shadow", {{"mode", "tinted"}, {"strength", "0.25"}})).shading;
    EXPECT_EQ(tinted.shadows, true);
    EXPECT_EQ(tinted.shadowStrength, 0.25f);
    EXPECT_EQ(tinted.shadowTint, glm::vec3(0.3f, 0.3f, 0.5f));
    EXPECT_THROW(lens("shadow", {{"mode", "dim"}}), Error);
}

TEST_F(InTreeLensPluginsTest, ShadowLensCastersNarrowShadowRaysOnly) {
    const LensContribution c = contribution(lens("shadow", {{"casters", "1"}}));
    EXPECT_EQ(c.visibility[kShadow].layerMask, layerBit(1));
    EXPECT_EQ(c.visibility[kPrimary].layerMask, kAllLayers);
}

TEST_F(InTreeLensPluginsTest, MagnifierScalesAboutTheRegionCentre) {
    std::shared_ptr<Lens> magnifier = registry->create("magnifier");
    const glm::vec2 center(0.3f, 0.6f);
    magnifier->setRegion(LensRegion::ellipse(center, glm::vec2(0.2f)));
    magnifier->setPropertyText("magnification", "4");
    magnifier->commit();
    const glm::mat3 &map = contribution(magnifier).sampleFromScreen;
    const auto apply = [&](const glm::vec2 &p) { return glm::vec2(map * glm::vec3(p, 1.f)); };
    EXPECT_NEAR(glm::length(apply(center) - center), 0.f, 1e-6f);
    EXPECT_NEAR(glm::length(apply(center + glm::vec2(0.2f, -0.08f)) - (center + glm::vec2(0.05f, -0.02f))), 0.f,
                1e-6f);
    EXPECT_THROW(lens("magnifier", {{"magnification", "0.5"}}), Error);
}

} // namespace
} // namespace mvcl
