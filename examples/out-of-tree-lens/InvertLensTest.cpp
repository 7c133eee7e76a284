// Unit test of the invert lens, built against an installed mvcl with mvcl::testing: the
// conformance suite on the statically linked lens, and what the lens does to pixels of a small
// scene and how it composes with another lens.

#include <mvcl/lens/LensRegistry.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/testing/LensConformanceSuite.h>
#include <mvcl/testing/LensTestScene.h>

#include <gtest/gtest.h>

using namespace mvcl;
using mvcl::test::LensTestScene;

// Every conformance check on the lens: tests LensConformance/invert.<check>.
MVCL_LENS_CONFORMANCE_TESTS(invert);

namespace {

/// The lens types this test can create: invert (linked in) only.
const LensRegistry &lenses() {
    static LensRegistry registry;
    static const bool added = (registry.add(mvcl_lens_plugin_invert()), true);
    (void)added;
    return registry;
}

std::shared_ptr<Lens> invertLens(const LensRegion &region, double amount = 1.0) {
    std::shared_ptr<Lens> lens = lenses().create("invert");
    lens->setRegion(region);
    lens->setProperty("amount", PropertyValue::real(amount));
    lens->commit();
    return lens;
}

constexpr int kWidth = 64, kHeight = 48;

} // namespace

TEST(InvertLens, NegatesTheColourUnderItAndNothingElse) {
    const LensTestScene scene = LensTestScene::builtin("cube-in-cube", kWidth, kHeight);
    LensStack stack;
    stack.add(invertLens(LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f})));
    const LensTestScene::Probe with = scene.probe(stack);
    const LensTestScene::Probe without = scene.probe(LensStack{});

    // Inside: lens 0 covers the pixel fully, the surface hit is the same, the colour negated.
    const int cx = kWidth / 2, cy = kHeight / 2;
    EXPECT_FLOAT_EQ(with.lensWeight(0, cx, cy), 1.f);
    ASSERT_EQ(with.lenses(cx, cy).size(), 1u);
    EXPECT_EQ(with.primaryHitLayer(cx, cy), without.primaryHitLayer(cx, cy)) << "a colour lens moves no ray";
    const glm::vec3 plain = without.radiance(cx, cy), negated = with.radiance(cx, cy);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(negated[c], 1.f - plain[c], 1e-5f) << "channel " << c;

    // Outside: no lens, the pixel's radiance is untouched.
    EXPECT_FLOAT_EQ(with.lensWeight(0, 2, 2), 0.f);
    EXPECT_TRUE(with.lenses(2, 2).empty());
    EXPECT_EQ(with.radiance(2, 2), without.radiance(2, 2));
}

TEST(InvertLens, TwoFullInvertsCancelAndHalfAmountsDoNot) {
    const LensTestScene scene = LensTestScene::builtin("cube-in-cube", kWidth, kHeight);
    const LensRegion everywhere = LensRegion::rectangle({0.5f, 0.5f}, {1.f, 1.f});
    const int cx = kWidth / 2, cy = kHeight / 2;
    const glm::vec3 plain = scene.probe(LensStack{}).radiance(cx, cy);

    LensStack twice;
    twice.add(invertLens(everywhere));
    twice.add(invertLens(everywhere));
    const glm::vec3 back = scene.probe(twice).radiance(cx, cy);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], plain[c], 1e-5f);

    // amount 0.5 maps every colour to 0.5: twice is still 0.5, not the original.
    LensStack halves;
    halves.add(invertLens(everywhere, 0.5));
    halves.add(invertLens(everywhere, 0.5));
    const glm::vec3 grey = scene.probe(halves).radiance(cx, cy);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(grey[c], 0.5f, 1e-5f);
}

TEST(InvertLens, FeatheredEdgeBlendsTheLensByItsWeight) {
    const LensTestScene scene = LensTestScene::builtin("cube-in-cube", kWidth, kHeight);
    LensRegion region = LensRegion::ellipse({0.5f, 0.5f}, {0.6f, 0.6f});
    region.setFeather(6.f);
    LensStack stack;
    stack.add(invertLens(region));
    const LensTestScene::Probe probe = scene.probe(stack);
    const LensTestScene::Probe without = scene.probe(LensStack{});

    // Somewhere along the middle row the lens covers a pixel partly: its radiance is the blend.
    bool sawEdge = false;
    for (int x = 0; x < kWidth; ++x) {
        const float w = probe.lensWeight(0, x, kHeight / 2);
        if (w <= 0.f || w >= 1.f) continue;
        sawEdge = true;
        const glm::vec3 plain = without.radiance(x, kHeight / 2);
        const glm::vec3 expected = (1.f - w) * plain + w * (glm::vec3(1.f) - plain);
        const glm::vec3 actual = probe.radiance(x, kHeight / 2);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-4f) << "x " << x << ", weight " << w;
    }
    EXPECT_TRUE(sawEdge) << "no pixel on the feathered edge";
}
