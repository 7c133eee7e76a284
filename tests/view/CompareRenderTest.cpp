// Compare mode of a RenderSession: two lens stacks split by a divider. The spliced image is
// the left stack's image left of the divider and the right stack's right of it, bit for bit;
// moving the divider re-traces only pixels between the old and new column; PolicyMap::splice.

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/lens/PolicyMap.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include "view/PluginLens.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mvcl::test {
namespace {

RenderSettings settingsOf(int width, int height) {
    RenderSettings s;
    s.width = width;
    s.height = height;
    s.samplesPerPixel = 1;
    s.tileSize = 8;
    s.previewBudgetSeconds = 0.0;
    return s;
}

/// A layer lens over most of the image that hides the outer cube: it differs from no lens
/// wherever the outer cube is seen.
LensStack revealStack() {
    LensStack stack;
    stack.add(pluginLens("layer", LensRegion::rectangle({0.5f, 0.5f}, {0.9f, 0.9f}), {{"layers", "1-"}}));
    return stack;
}

Framebuffer renderedImage(RenderSession &session) {
    session.renderUntilIdle();
    return session.image();
}

TEST(CompareRenderTest, TheSplicedImageIsEachStacksOwnImageOnItsSide) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    const RenderSettings settings = settingsOf(96, 64);
    const LensStack left = revealStack(), right;
    const auto render = [&](const std::function<void(RenderSession &)> &setStacks) {
        RenderSession session(tracer);
        session.setSettings(settings);
        session.setCamera(camera);
        setStacks(session);
        return renderedImage(session);
    };
    const Framebuffer leftOnly = render([&](RenderSession &s) { s.setLensStack(left); });
    const Framebuffer rightOnly = render([&](RenderSession &s) { s.setLensStack(right); });
    const Framebuffer spliced = render([&](RenderSession &s) { s.setLensStacks(left, right, 0.5f); });
    int differing = 0;
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) {
            const Framebuffer &expected = x < 48 ? leftOnly : rightOnly;
            ASSERT_EQ(spliced.at(x, y), expected.at(x, y)) << x << "," << y;
            differing += !(leftOnly.at(x, y) == rightOnly.at(x, y));
        }
    EXPECT_GT(differing, 500); // the stacks do show different things
}

TEST(CompareRenderTest, MovingTheDividerEightPixelsReTracesOnlyThePixelsItPasses) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    const RenderSettings settings = settingsOf(200, 100);
    const LensStack left = revealStack(), right;
    RenderSession session(tracer);
    session.setSettings(settings);
    session.setCamera(Camera::fromDesc(scene.cameras.front()));
    session.setLensStacks(left, right, 0.5f);
    const Framebuffer before = renderedImage(session);

    session.setLensStacks(left, right, 0.54f); // column 100 → 108
    const RenderPassStats pass = session.renderPass();
    EXPECT_EQ(pass.kind, PassKind::Retrace);
    // At most the 8 × 100 strip, and only where the two stacks differ (inside the lens).
    EXPECT_GT(pass.pixelsRestarted, 0u);
    EXPECT_LE(pass.pixelsRestarted, 8u * 100u);
    EXPECT_EQ(pass.pixelsTraced, pass.pixelsRestarted);
    session.renderUntilIdle();
    const Framebuffer &after = session.image();
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) {
            if (x < 100 || x >= 108) {
                ASSERT_EQ(after.at(x, y), before.at(x, y)) << x << "," << y;
            }
        }

    // Moving it back restores the image bit for bit, and again touches only that strip.
    session.setLensStacks(left, right, 0.5f);
    EXPECT_LE(session.renderPass().pixelsRestarted, 8u * 100u);
    session.renderUntilIdle();
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) ASSERT_EQ(session.image().at(x, y), before.at(x, y));

    // Leaving compare mode re-composes the whole image with the left stack.
    session.setLensStack(left);
    EXPECT_GT(session.renderPass().pixelsRestarted, 0u);
}

TEST(CompareRenderTest, AnEditOfOneSidesStackReTracesOnlyThatSide) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    const RenderSettings settings = settingsOf(200, 100);
    const LensStack left = revealStack(), right = revealStack(); // the same lens on both sides
    RenderSession session(tracer);
    session.setSettings(settings);
    session.setCamera(Camera::fromDesc(scene.cameras.front()));
    session.setLensStacks(left, right, 0.5f);
    const Framebuffer before = renderedImage(session);

    // The right side's lens shrinks to the middle: its left half, under the divider, is hidden.
    LensRegion smaller = right.lens(0)->region();
    smaller.setSize({0.5f, 0.5f});
    right.lens(0)->setRegion(smaller);
    right.lens(0)->commit();
    session.setLensStacks(left, right, 0.5f);
    const RenderPassStats pass = session.renderPass();
    EXPECT_EQ(pass.kind, PassKind::Retrace);
    EXPECT_GT(pass.pixelsRestarted, 0u);
    EXPECT_LT(pass.pixelsRestarted, 100u * 100u); // within the right half
    session.renderUntilIdle();
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < 100; ++x) ASSERT_EQ(session.image().at(x, y), before.at(x, y)) << x << "," << y;
}

TEST(CompareRenderTest, SpliceTakesColumnsFromEachMapAndShiftsTheRightLensSets) {
    PolicyMap left(4, 2, RayPolicy{});
    PixelPolicy lensed;
    lensed.ray.query(RayType::Primary).layerMask = 2;
    lensed.lensSet = 1;
    const uint16_t l1 = left.addPolicy(lensed);
    for (int x = 0; x < 4; ++x) left.setPixel(x, 0, l1);
    PolicyMap right(4, 2, RayPolicy{});
    lensed.ray.query(RayType::Primary).layerMask = 4;
    const uint16_t r1 = right.addPolicy(lensed);
    const PolicyTerm blend[] = {{0, 0.5f}, {r1, 0.5f}};
    for (int x = 0; x < 4; ++x) right.setPixelBlend(x, 1, blend);

    const PolicyMap spliced = PolicyMap::splice(left, right, 2, 3);
    ASSERT_EQ(spliced.policies().size(), 4u);
    EXPECT_EQ(spliced.dominantPolicy(1, 0).ray.query(RayType::Primary).layerMask, 2u); // left's
    EXPECT_EQ(spliced.dominantPolicy(2, 0).ray.query(RayType::Primary).layerMask, kAllLayers); // right's base
    EXPECT_EQ(spliced.terms(1, 1).size(), 1u);
    ASSERT_EQ(spliced.terms(3, 1).size(), 2u); // right's blend
    EXPECT_EQ(spliced.policy(spliced.terms(3, 1)[1].policy).ray.query(RayType::Primary).layerMask, 4u);
    EXPECT_EQ(spliced.policy(spliced.terms(3, 1)[1].policy).lensSet, uint64_t(1) << 3);
    EXPECT_THROW(PolicyMap::splice(left, PolicyMap(3, 2, RayPolicy{}), 1, 1), Error);
}

} // namespace
} // namespace mvcl::test
