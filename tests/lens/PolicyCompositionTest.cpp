// The lens composition rules (docs/architecture.md), one rule per test, on random data.
#include <mvcl/lens/PolicyComposition.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace mvcl;

namespace {

ClipVolume randomClip(std::mt19937 &rng) {
    // Drawn from a small pool so that equal volumes occur and idempotence is exercised.
    std::uniform_int_distribution<int> pick(0, 5);
    const int k = pick(rng);
    const ClipVolume::Keep keep = k < 3 ? ClipVolume::Keep::Outside : ClipVolume::Keep::Inside;
    const glm::vec3 p(float(k), 0.f, -float(k));
    switch (k % 3) {
    case 0: return ClipVolume::box(p, p + glm::vec3(1.f), keep);
    case 1: return ClipVolume::sphere(p, 0.5f + float(k), keep);
    default: return ClipVolume::halfSpace(p + glm::vec3(0.f, 1.f, 0.f), 0.5f + float(k), keep);
    }
}

RayQuery randomQuery(std::mt19937 &rng) {
    std::uniform_real_distribution<float> t(0.f, 10.f);
    RayQuery q;
    q.layerMask = uint32_t(rng());
    q.tMin = t(rng);
    q.tMax = rng() % 4 == 0 ? q.tMax : q.tMin + t(rng);
    const int clips = int(rng() % 3);
    for (int i = 0; i < clips; ++i) q = intersectQueries(q, [&] {
        RayQuery c;
        c.addClip(randomClip(rng));
        return c;
    }());
    return q;
}

/// Equal constraints: same mask and range, and the same set of clip volumes in any order.
void expectSameConstraint(const RayQuery &a, const RayQuery &b) {
    EXPECT_EQ(a.layerMask, b.layerMask);
    EXPECT_EQ(a.tMin, b.tMin);
    EXPECT_EQ(a.tMax, b.tMax);
    ASSERT_EQ(a.clipCount(), b.clipCount());
    for (const ClipVolume &c : a.clips())
        EXPECT_NE(std::find(b.clips().begin(), b.clips().end(), c), b.clips().end());
}

ColorPolicy randomColor(std::mt19937 &rng) {
    std::uniform_real_distribution<float> v(-1.f, 1.f);
    ColorPolicy c;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) c.matrix[i][j] = v(rng);
        c.offset[i] = v(rng);
    }
    return c;
}

void expectNear(const ColorPolicy &a, const ColorPolicy &b, float tolerance) {
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(a.matrix[i][j], b.matrix[i][j], tolerance);
        EXPECT_NEAR(a.offset[i], b.offset[i], tolerance);
    }
}

} // namespace

TEST(PolicyComposition, TheEmptyConstraintIsTheIdentity) {
    std::mt19937 rng(1);
    for (int i = 0; i < 200; ++i) {
        const RayQuery q = randomQuery(rng);
        expectSameConstraint(intersectQueries(q, RayQuery{}), q);
        expectSameConstraint(intersectQueries(RayQuery{}, q), q);
    }
}

TEST(PolicyComposition, VisibilityIsCommutativeAssociativeAndIdempotent) {
    std::mt19937 rng(2);
    for (int i = 0; i < 500; ++i) {
        const RayQuery a = randomQuery(rng), b = randomQuery(rng), c = randomQuery(rng);
        expectSameConstraint(intersectQueries(a, b), intersectQueries(b, a));
        expectSameConstraint(intersectQueries(intersectQueries(a, b), c),
                             intersectQueries(a, intersectQueries(b, c)));
        expectSameConstraint(intersectQueries(a, a), a);
    }
}

TEST(PolicyComposition, VisibilityNarrowsEveryField) {
    RayQuery a, b;
    a.layerMask = layersFrom(1);
    a.tMin = 2.f;
    b.layerMask = layerBit(0) | layerBit(2);
    b.tMax = 5.f;
    const RayQuery q = intersectQueries(a, b);
    EXPECT_EQ(q.layerMask, layerBit(2));
    EXPECT_EQ(q.tMin, 2.f);
    EXPECT_EQ(q.tMax, 5.f);
}

TEST(PolicyComposition, TooManyClipVolumesAreCountedNeverThrown) {
    RayQuery a, b;
    for (int i = 0; i < kMaxClipVolumes; ++i) {
        a.addClip(ClipVolume::sphere(glm::vec3(0.f), float(i), ClipVolume::Keep::Outside));
        b.addClip(ClipVolume::sphere(glm::vec3(0.f), float(100 + i), ClipVolume::Keep::Outside));
    }
    EXPECT_THROW(a.addClip(ClipVolume::sphere(glm::vec3(1.f), 1.f, ClipVolume::Keep::Outside)), Error);
    int dropped = 0;
    EXPECT_EQ(intersectQueries(a, a, &dropped), a); // identical volumes are kept once
    EXPECT_EQ(dropped, 0);
    const RayQuery q = intersectQueries(a, b, &dropped);
    EXPECT_EQ(dropped, kMaxClipVolumes); // spheres do not merge: all of b's are left out
    EXPECT_EQ(q.clipCount(), kMaxClipVolumes);
}

TEST(PolicyComposition, FullQueriesMergeBoxesKeptInsideAndParallelHalfSpaces) {
    RayQuery a, b;
    for (int i = 0; i < kMaxClipVolumes - 2; ++i)
        a.addClip(ClipVolume::sphere(glm::vec3(0.f), float(i), ClipVolume::Keep::Outside));
    a.addClip(ClipVolume::box(glm::vec3(0.f), glm::vec3(2.f), ClipVolume::Keep::Inside));
    a.addClip(ClipVolume::halfSpace({0.f, 1.f, 0.f}, 1.f, ClipVolume::Keep::Outside));
    b.addClip(ClipVolume::box(glm::vec3(1.f), glm::vec3(3.f), ClipVolume::Keep::Inside));
    b.addClip(ClipVolume::halfSpace({0.f, 1.f, 0.f}, 0.5f, ClipVolume::Keep::Outside));
    int dropped = 0;
    const RayQuery q = intersectQueries(a, b, &dropped);
    EXPECT_EQ(dropped, 0);
    ASSERT_EQ(q.clipCount(), kMaxClipVolumes);
    // The merged query accepts exactly the points both accept.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coordinate(-1.f, 4.f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        EXPECT_EQ(q.acceptsPoint(p, 0), a.acceptsPoint(p, 0) && b.acceptsPoint(p, 0));
    }
}

TEST(PolicyComposition, VolumesOnOtherLayersOrAxesOrCapsNeverMerge) {
    // Merging a pair into one volume is exact only when both act on the same layers, turn the
    // same way and draw the same caps; otherwise both stay or one is counted as dropped.
    const auto full = [] {
        RayQuery q;
        for (int i = 0; i < kMaxClipVolumes - 1; ++i)
            q.addClip(ClipVolume::sphere(glm::vec3(0.f), float(i), ClipVolume::Keep::Outside));
        q.addClip(ClipVolume::box(glm::vec3(0.f), glm::vec3(2.f), ClipVolume::Keep::Inside));
        return q;
    };
    ClipVolume otherLayers = ClipVolume::box(glm::vec3(1.f), glm::vec3(3.f), ClipVolume::Keep::Inside);
    otherLayers.setLayerMask(layerBit(1));
    const float c = std::cos(0.3f), s = std::sin(0.3f);
    const ClipVolume turned = ClipVolume::orientedBox(glm::vec3(2.f), glm::vec3(1.f),
                                                      glm::mat3({c, s, 0.f}, {-s, c, 0.f}, {0.f, 0.f, 1.f}),
                                                      ClipVolume::Keep::Inside);
    ClipVolume capped = ClipVolume::box(glm::vec3(1.f), glm::vec3(3.f), ClipVolume::Keep::Inside);
    capped.setCapStyle(ClipVolume::CapStyle::Hatched);
    for (const ClipVolume &clip : {otherLayers, turned, capped}) {
        RayQuery b;
        b.addClip(clip);
        int dropped = 0;
        const RayQuery q = intersectQueries(full(), b, &dropped);
        EXPECT_EQ(dropped, 1);
        EXPECT_EQ(q, full());
    }
    // The same layers, axes and caps: merged, and exact.
    ClipVolume sameLayers = ClipVolume::box(glm::vec3(1.f), glm::vec3(3.f), ClipVolume::Keep::Inside);
    RayQuery a = full(), b;
    b.addClip(sameLayers);
    int dropped = 0;
    const RayQuery q = intersectQueries(a, b, &dropped);
    EXPECT_EQ(dropped, 0);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> coordinate(-1.f, 4.f);
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        for (uint32_t layer : {0u, 1u})
            EXPECT_EQ(q.acceptsPoint(p, layer), a.acceptsPoint(p, layer) && b.acceptsPoint(p, layer));
    }
}

TEST(PolicyComposition, ColourIsFunctionCompositionBottomToTop) {
    std::mt19937 rng(3);
    for (int i = 0; i < 100; ++i) {
        const ColorPolicy lower = randomColor(rng), upper = randomColor(rng), top = randomColor(rng);
        const ColorPolicy both = composeColor(lower, upper);
        const glm::vec3 c(0.3f, -0.2f, 0.9f);
        const glm::vec3 expected = upper.matrix * (lower.matrix * c + lower.offset) + upper.offset;
        const glm::vec3 got = both.matrix * c + both.offset;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 1e-5f);
        expectNear(composeColor(composeColor(lower, upper), top), composeColor(lower, composeColor(upper, top)), 1e-4f);
        expectNear(composeColor(ColorPolicy{}, lower), lower, 0.f);
        expectNear(composeColor(lower, ColorPolicy{}), lower, 0.f);
    }
}

TEST(PolicyComposition, ColourOrderMattersForNonCommutingMaps) {
    ColorPolicy grey; // luminance to all channels
    for (int i = 0; i < 3; ++i) grey.matrix[i] = glm::vec3(1.f / 3.f);
    ColorPolicy redTint;
    redTint.matrix = glm::mat3(glm::vec3(1.f, 0.f, 0.f), glm::vec3(0.f, 0.2f, 0.f), glm::vec3(0.f, 0.f, 0.2f));
    const glm::vec3 white(1.f);
    const ColorPolicy tintThenGrey = composeColor(redTint, grey);
    const ColorPolicy greyThenTint = composeColor(grey, redTint);
    const glm::vec3 a = tintThenGrey.matrix * white, b = greyThenTint.matrix * white;
    EXPECT_NEAR(a.r, a.g, 1e-6f) << "grey on top leaves a grey pixel";
    EXPECT_GT(b.r, 2.f * b.g) << "the tint on top leaves a red pixel";
}

TEST(PolicyComposition, UpperShadingOverridesOnlyTheFieldsItSets) {
    PixelPolicy base;
    base.ray.shading.maxDepth = 5;
    LensContribution lower, upper;
    lower.shading.shadows = false;
    lower.shading.shadowStrength = 0.25f;
    upper.shading.shadows = true;
    upper.shading.reflections = false;
    const PixelPolicy p = applyContribution(applyContribution(base, lower), upper);
    EXPECT_TRUE(p.ray.shading.shadows);
    EXPECT_EQ(p.ray.shading.shadowStrength, 0.25f);
    EXPECT_FALSE(p.ray.shading.reflections);
    EXPECT_TRUE(p.ray.shading.refractions);
    EXPECT_EQ(p.ray.shading.maxDepth, 5);
    const PixelPolicy swapped = applyContribution(applyContribution(base, upper), lower);
    EXPECT_FALSE(swapped.ray.shading.shadows) << "order decides between conflicting overrides";
}

TEST(PolicyComposition, TheUpperLensLooksAtTheLowerLensImage) {
    // Lower: shift right by 0.1. Upper: magnify 2× about (0.5, 0.5). A pixel at u looks, through
    // the upper lens, at 0.5 + (u − 0.5)/2 of the lower image, which shows the scene at +0.1.
    LensContribution shift, magnify;
    shift.sampleFromScreen[2] = glm::vec3(0.1f, 0.f, 1.f);
    magnify.sampleFromScreen = glm::mat3(glm::vec3(0.5f, 0.f, 0.f), glm::vec3(0.f, 0.5f, 0.f), glm::vec3(0.25f, 0.25f, 1.f));
    const PixelPolicy p = applyContribution(applyContribution(PixelPolicy{}, shift), magnify);
    const glm::vec2 s = p.samplePosition({90.f, 50.f}, 100, 100); // u = (0.9, 0.5)
    EXPECT_NEAR(s.x, 100.f * (0.5f + 0.4f / 2.f + 0.1f), 1e-4f);
    EXPECT_NEAR(s.y, 50.f, 1e-4f);
    EXPECT_FALSE(applyContribution(PixelPolicy{}, LensContribution{}).isShaped());
}
