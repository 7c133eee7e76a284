// Where lenses do not declare that they commute, order matters: swapping two of them changes
// what the pixels in their overlap do. And PixelProbe, the helper a plugin author tests with,
// answers what a pixel's primary ray hits under a stack without rendering an image.

#include "InTreeLensRegistry.h"
#include <mvcl/testing/LensConformance.h>
#include "TestLenses.h"

#include <mvcl/view/PixelProbe.h>

#include <gtest/gtest.h>

using namespace mvcl;
using namespace mvcl::test;

namespace {

constexpr int kWidth = kConformanceWidth;
constexpr int kHeight = kConformanceHeight;
constexpr uint64_t kBothLenses = 0b11;

std::shared_ptr<Lens> makeLens(const std::string &type, const LensRegion &region,
                               std::initializer_list<std::pair<const char *, const char *>> properties) {
    std::shared_ptr<Lens> lens = inTreeLenses().registry.create(type);
    for (const auto &[key, text] : properties) lens->setPropertyText(key, text);
    lens->setRegion(region);
    lens->commit();
    return lens;
}

// Two overlapping regions, left and right of the centre.
const LensRegion kLeft = LensRegion::rectangle({0.4f, 0.5f}, {0.5f, 0.6f});
const LensRegion kRight = LensRegion::ellipse({0.6f, 0.5f}, {0.5f, 0.6f});

/// Pixels (x, y) where both lenses of a two-lens stack apply fully.
std::vector<std::pair<int, int>> overlapPixels(const PolicyMap &map) {
    std::vector<std::pair<int, int>> pixels;
    for (int y = 0; y < map.height(); ++y)
        for (int x = 0; x < map.width(); ++x)
            if (map.terms(x, y).size() == 1 && map.dominantPolicy(x, y).lensSet == kBothLenses)
                pixels.emplace_back(x, y);
    return pixels;
}

/// Number of overlap pixels whose rendered colour changes when the two lenses swap.
int changedOverlapPixels(const std::shared_ptr<Lens> &lower, const std::shared_ptr<Lens> &upper) {
    const PolicyMap forward = stackOf({lower, upper}).compose(RayPolicy{}, kWidth, kHeight);
    const PolicyMap swapped = stackOf({upper, lower}).compose(RayPolicy{}, kWidth, kHeight);
    const Framebuffer a = renderMap(forward), b = renderMap(swapped);
    int changed = 0;
    for (const auto &[x, y] : overlapPixels(forward))
        changed += a.at(x, y) != b.at(x, y) ? 1 : 0;
    return changed;
}

} // namespace

TEST(OrderEffects, UpperShadowLensWinsInTheOverlap) {
    const auto shadowsOn = makeLens("shadow", kLeft, {{"mode", "on"}});
    const auto shadowsOff = makeLens("shadow", kRight, {{"mode", "off"}});
    ASSERT_FALSE(shadowsOn->info().algebra.commutes);
    const PixelPolicy onBelow = stackOf({shadowsOn, shadowsOff}).composeSet(RayPolicy{}, kBothLenses);
    const PixelPolicy offBelow = stackOf({shadowsOff, shadowsOn}).composeSet(RayPolicy{}, kBothLenses);
    EXPECT_FALSE(onBelow.rendersLike(offBelow));
    EXPECT_FALSE(onBelow.ray.shading.shadows);
    EXPECT_TRUE(offBelow.ray.shading.shadows);
    // Outside the overlap each lens acts alone, whatever the order.
    EXPECT_TRUE(stackOf({shadowsOn, shadowsOff}).composeSet(RayPolicy{}, 0b01)
                    .rendersLike(stackOf({shadowsOff, shadowsOn}).composeSet(RayPolicy{}, 0b10)));
}

TEST(OrderEffects, MagnifierOverMagnifierDependsOnOrder) {
    const auto left = makeLens("magnifier", kLeft, {{"magnification", "2"}});
    const auto right = makeLens("magnifier", kRight, {{"magnification", "3"}});
    ASSERT_FALSE(left->info().algebra.commutes);
    const PixelPolicy leftBelow = stackOf({left, right}).composeSet(RayPolicy{}, kBothLenses);
    const PixelPolicy rightBelow = stackOf({right, left}).composeSet(RayPolicy{}, kBothLenses);
    EXPECT_NE(leftBelow.sampleFromScreen, rightBelow.sampleFromScreen);
    // Both orders magnify by 2·3 = 6; only where they look differs.
    EXPECT_NEAR(leftBelow.sampleFromScreen[0][0], 1.f / 6.f, 1e-6f);
    EXPECT_NEAR(rightBelow.sampleFromScreen[0][0], 1.f / 6.f, 1e-6f);
    EXPECT_GT(changedOverlapPixels(left, right), 0);
}

TEST(OrderEffects, AchromaticOverTintDiffersFromTintOverAchromatic) {
    const auto achromatic = makeLens("achromatic", kLeft, {{"amount", "1"}});
    const auto tint = makeTestLens<TintLens>(kRight);
    ASSERT_FALSE(tint->info().algebra.commutes);
    const PixelPolicy greyLast = stackOf({tint, achromatic}).composeSet(RayPolicy{}, kBothLenses);
    const PixelPolicy tintLast = stackOf({achromatic, tint}).composeSet(RayPolicy{}, kBothLenses);
    EXPECT_FALSE(greyLast.ray.color == tintLast.ray.color);
    // Grey last: every output channel is the same luminance, so the overlap has no hue.
    const glm::vec3 grey = greyLast.ray.color.matrix * glm::vec3(0.2f, 0.5f, 0.9f);
    EXPECT_FLOAT_EQ(grey.r, grey.g);
    EXPECT_FLOAT_EQ(grey.g, grey.b);
    EXPECT_GT(changedOverlapPixels(tint, achromatic), 0);
}

TEST(OrderEffects, CommutingLensesDoNotDependOnOrder) {
    // The counterpart of the tests above, on lenses that declare commutes: swapping changes
    // no overlap pixel, so the order effects above are not an artefact of swapping itself.
    const auto layer = makeLens("layer", kLeft, {{"layers", "1-"}});
    const auto achromatic = makeLens("achromatic", kRight, {{"amount", "0.7"}});
    ASSERT_TRUE(layer->info().algebra.commutes && achromatic->info().algebra.commutes);
    EXPECT_EQ(changedOverlapPixels(layer, achromatic), 0);
}

TEST(PixelProbe, LayerLensLetsPrimaryRaysUnderItSeeTheInnerCube) {
    const ConformanceScene &scene = conformanceScene();
    const auto layerLens = makeLens("layer", LensRegion::ellipse({0.5f, 0.5f}, {0.3f, 0.3f}),
                                    {{"layers", "1-"}});
    const PixelProbe probe(stackOf({layerLens}), kWidth, kHeight);
    const PixelProbe withoutLens(LensStack{}, kWidth, kHeight);

    // The centre pixel: its policy is the lens's, and its primary ray passes the outer cube
    // (layer 0) to hit the inner one (layer 1).
    const int cx = kWidth / 2, cy = kHeight / 2;
    EXPECT_EQ(probe.lensSet(cx, cy), 1u);
    EXPECT_EQ(probe.policy(cx, cy).ray.query(RayType::Primary).layerMask, layersFrom(1));
    EXPECT_EQ(withoutLens.primaryHitLayer(scene.tracer, scene.camera, cx, cy), 0);
    EXPECT_EQ(probe.primaryHitLayer(scene.tracer, scene.camera, cx, cy), 1);

    // Every other pixel: outside the lens the ray hits what it hits without one (layer 0 of
    // the outer cube among others); inside, never layer 0.
    int outsideOnOuterCube = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::optional<int> layer = probe.primaryHitLayer(scene.tracer, scene.camera, x, y);
            if (probe.lensSet(x, y) == 0) {
                EXPECT_EQ(layer, withoutLens.primaryHitLayer(scene.tracer, scene.camera, x, y))
                    << "outside the lens at (" << x << ", " << y << ")";
                outsideOnOuterCube += layer == 0 ? 1 : 0;
            } else {
                EXPECT_NE(layer, 0) << "inside the lens at (" << x << ", " << y << ")";
            }
        }
    EXPECT_GT(outsideOnOuterCube, 0);
}
