// LensStack: what each pixel's policy is under overlapping shapes and feathered edges, that
// policies are composed per overlap set and not per pixel, editing the stack, and costs.
#include <mvcl/lens/LensStack.h>

#include "lens/FixedLens.h"

#include <mvcl/core/Error.h>
#include <mvcl/testing/LensConformanceSupport.h>
#include <mvcl/view/Renderer.h>

#include <gtest/gtest.h>

#include <set>

using namespace mvcl;
using test::makeFixedLens;

namespace {

LensContribution layerMaskContribution(uint32_t mask) {
    LensContribution c;
    c.visibility[size_t(RayType::Primary)].layerMask = mask;
    return c;
}

LensContribution colorScaleContribution(float scale) {
    LensContribution c;
    c.color.matrix = glm::mat3(scale);
    return c;
}

uint32_t primaryMask(const PixelPolicy &p) { return p.ray.query(RayType::Primary).layerMask; }

} // namespace

TEST(LensStack, AnEmptyStackLeavesEveryPixelOnTheBase) {
    RayPolicy base;
    base.shading.maxDepth = 2;
    const PolicyMap map = LensStack().compose(base, 40, 30);
    EXPECT_EQ(map.policies().size(), 1u);
    EXPECT_EQ(map.blendedPixelCount(), 0u);
    EXPECT_EQ(map.dominantPolicy(20, 15).ray.shading.maxDepth, 2);
}

TEST(LensStack, OverlappingRectanglesGiveOnePolicyPerOverlapSet) {
    // A: left 60%, B: right 60%, on a large image: 4 sets (none, A, B, A∩B) whatever the size.
    LensStack stack;
    stack.add(makeFixedLens(layerMaskContribution(layersFrom(1)), LensRegion::rectangle({0.3f, 0.5f}, {0.6f, 1.f})));
    stack.add(makeFixedLens(layerMaskContribution(layerBit(0) | layerBit(2)), LensRegion::rectangle({0.7f, 0.5f}, {0.6f, 1.f})));
    const int w = 1000, h = 400;
    const PolicyMap map = stack.compose(RayPolicy{}, w, h);
    EXPECT_EQ(map.policies().size(), 4u);
    std::set<uint32_t> mixes;
    for (int y = 0; y < h; y += 7)
        for (int x = 0; x < w; x += 3) mixes.insert(map.mixIndex(x, y));
    EXPECT_EQ(mixes.size(), 3u) << "A only, A∩B, B only (the lenses cover the whole image)";

    EXPECT_EQ(map.dominantPolicy(100, 200).lensSet, 0b01u);
    EXPECT_EQ(primaryMask(map.dominantPolicy(100, 200)), layersFrom(1));
    EXPECT_EQ(map.dominantPolicy(500, 200).lensSet, 0b11u);
    EXPECT_EQ(primaryMask(map.dominantPolicy(500, 200)), layerBit(2)) << "visibility intersects";
    EXPECT_EQ(map.dominantPolicy(900, 200).lensSet, 0b10u);
    EXPECT_EQ(primaryMask(map.dominantPolicy(900, 200)), layerBit(0) | layerBit(2));
}

TEST(LensStack, PixelsOutsideEveryLensKeepTheBasePolicy) {
    LensStack stack;
    stack.add(makeFixedLens(layerMaskContribution(layerBit(1)), LensRegion::ellipse({0.5f, 0.5f}, {0.2f, 0.2f})));
    const PolicyMap map = stack.compose(RayPolicy{}, 100, 100);
    int inside = 0;
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 100; ++x) {
            const float dx = (float(x) + 0.5f - 50.f) / 10.f, dy = (float(y) + 0.5f - 50.f) / 10.f;
            const bool in = dx * dx + dy * dy <= 1.f;
            inside += in;
            EXPECT_EQ(map.terms(x, y)[0].policy != 0, in) << x << "," << y;
        }
    EXPECT_NEAR(inside, 314, 12);
}

TEST(LensStack, AFeatheredEdgeBlendsWithAndWithoutTheLensByCoverage) {
    LensRegion region = LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f});
    region.setFeather(10.f);
    LensStack stack;
    stack.add(makeFixedLens(colorScaleContribution(0.5f), region));
    const int w = 200, h = 200;
    const PolicyMap map = stack.compose(RayPolicy{}, w, h);
    EXPECT_EQ(map.policies().size(), 2u);
    EXPECT_GT(map.blendedPixelCount(), 0u);
    for (int x = 40; x < 100; ++x) {
        const auto terms = map.terms(x, 100);
        float withLens = 0.f, total = 0.f;
        for (const PolicyTerm &t : terms) {
            total += t.weight;
            if (map.policy(t.policy).lensSet == 1u) withLens += t.weight;
        }
        EXPECT_NEAR(total, 1.f, 1e-6f);
        const float coverage = region.coverage({float(x) + 0.5f, 100.5f}, w, h);
        EXPECT_NEAR(withLens, coverage, 1e-6f) << "x=" << x;
        EXPECT_EQ(terms.size() > 1, coverage > 0.f && coverage < 1.f);
    }
}

TEST(LensStack, TwoFeatheredEdgesBlendEverySubsetByProductWeights) {
    LensRegion a = LensRegion::rectangle({0.4f, 0.5f}, {0.4f, 0.8f});
    LensRegion b = LensRegion::rectangle({0.6f, 0.5f}, {0.4f, 0.8f});
    a.setFeather(30.f);
    b.setFeather(30.f);
    LensStack stack;
    stack.add(makeFixedLens(colorScaleContribution(0.5f), a));
    stack.add(makeFixedLens(colorScaleContribution(0.25f), b));
    const int w = 100, h = 100;
    const PolicyMap map = stack.compose(RayPolicy{}, w, h);
    // Pixel (55, 50) lies in both feather bands (edges at x=40 of B and x=60 of A, 30 px wide).
    const float wa = a.coverage({55.5f, 50.5f}, w, h), wb = b.coverage({55.5f, 50.5f}, w, h);
    ASSERT_GT(wa, 0.f);
    ASSERT_LT(wa, 1.f);
    ASSERT_GT(wb, 0.f);
    ASSERT_LT(wb, 1.f);
    const auto terms = map.terms(55, 50);
    ASSERT_EQ(terms.size(), 4u);
    for (const PolicyTerm &t : terms) {
        const uint64_t set = map.policy(t.policy).lensSet;
        const float expected = ((set & 1u) ? wa : 1.f - wa) * ((set & 2u) ? wb : 1.f - wb);
        EXPECT_NEAR(t.weight, expected, 1e-6f) << "set " << set;
    }
    EXPECT_EQ(map.policies().size(), 4u) << "composed per set, not per pixel";
}

TEST(LensStack, DisabledLensesAndLensesOffScreenChangeNothing) {
    auto lens = makeFixedLens(layerMaskContribution(layerBit(1)), LensRegion{});
    LensStack stack;
    stack.add(lens);
    stack.add(makeFixedLens(layerMaskContribution(layerBit(1)), LensRegion::rectangle({3.f, 3.f}, {0.5f, 0.5f})));
    lens->setEnabled(false);
    EXPECT_EQ(stack.compose(RayPolicy{}, 50, 50).policies().size(), 2u) << "staged only";
    lens->commit();
    const PolicyMap map = stack.compose(RayPolicy{}, 50, 50);
    EXPECT_EQ(map.policies().size(), 1u);
    EXPECT_EQ(map.dominantPolicy(25, 25).lensSet, 0u);
}

TEST(LensStack, ReorderingChangesTheOrderColourMapsApplyIn) {
    LensContribution grey, tint;
    for (int i = 0; i < 3; ++i) grey.color.matrix[i] = glm::vec3(1.f / 3.f);
    tint.color.matrix = glm::mat3(glm::vec3(1.f, 0.f, 0.f), glm::vec3(0.f, 0.f, 0.f), glm::vec3(0.f, 0.f, 0.f));
    LensStack stack;
    stack.add(makeFixedLens(grey, LensRegion{}));
    stack.add(makeFixedLens(tint, LensRegion{}));
    const glm::vec3 white(1.f);
    const glm::vec3 greyThenTint = stack.compose(RayPolicy{}, 8, 8).dominantPolicy(4, 4).ray.color.matrix * white;
    EXPECT_EQ(greyThenTint.g, 0.f);
    stack.move(1, 0);
    const glm::vec3 tintThenGrey = stack.compose(RayPolicy{}, 8, 8).dominantPolicy(4, 4).ray.color.matrix * white;
    EXPECT_NEAR(tintThenGrey.g, 1.f / 3.f, 1e-6f);
    stack.remove(0);
    EXPECT_EQ(stack.size(), 1);
    EXPECT_THROW(stack.remove(3), Error);
    EXPECT_THROW(stack.move(0, 1), Error);
}

TEST(LensStack, HoldsAtMostSixtyFourLenses) {
    LensStack stack;
    for (int i = 0; i < LensStack::kMaxLenses; ++i) stack.add(makeFixedLens({}, LensRegion{}));
    EXPECT_THROW(stack.add(makeFixedLens({}, LensRegion{})), Error);
    EXPECT_THROW(stack.add(nullptr), Error);
    // All 64 overlap fully: one set, bit 63 included.
    auto last = makeFixedLens(layerMaskContribution(layerBit(3)), LensRegion{});
    stack.remove(63);
    stack.add(last);
    EXPECT_EQ(stack.compose(RayPolicy{}, 10, 10).dominantPolicy(5, 5).lensSet, uint64_t(1) << 63);
}

TEST(LensStack, CostsCountThePixelsAndRaysUnderEachLens) {
    const test::ConformanceScene &scene = test::conformanceScene();
    LensStack stack;
    stack.add(makeFixedLens(layerMaskContribution(layerBit(1)), LensRegion::rectangle({0.25f, 0.5f}, {0.5f, 1.f})));
    stack.add(makeFixedLens(colorScaleContribution(0.5f), LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 1.f})));
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.samplesPerPixel = 1;
    settings.threads = 2;
    const PolicyMap map = stack.compose(RayPolicy{}, settings.width, settings.height);
    Framebuffer image;
    const RenderStats stats = Renderer(scene.tracer).render(scene.camera, map, settings, image);
    ASSERT_EQ(stats.perPolicy.size(), map.policies().size());
    uint64_t pixels = 0, rays = 0;
    for (const PolicyCost &c : stats.perPolicy) {
        pixels += c.pixels;
        rays += c.rays;
    }
    EXPECT_EQ(pixels, stats.pixels);
    EXPECT_EQ(rays, stats.rays.total());
    const std::vector<LensCost> costs = stack.costs(map, stats.perPolicy);
    ASSERT_EQ(costs.size(), 2u);
    EXPECT_EQ(costs[0].pixels, 32u * 48u);
    EXPECT_EQ(costs[1].pixels, 32u * 48u);
    EXPECT_GE(costs[0].rays, costs[0].pixels);
    EXPECT_GT(costs[0].milliseconds, 0.0);
}
