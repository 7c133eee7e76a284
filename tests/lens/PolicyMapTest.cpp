#include <mvcl/lens/PolicyMap.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <vector>

using namespace mvcl;

TEST(PolicyMap, EveryPixelStartsOnTheBasePolicy) {
    RayPolicy base;
    base.shading.maxDepth = 3;
    const PolicyMap map(4, 3, base);
    ASSERT_EQ(map.policies().size(), 1u);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            ASSERT_EQ(map.terms(x, y).size(), 1u);
            EXPECT_EQ(map.terms(x, y)[0].policy, 0);
            EXPECT_EQ(map.terms(x, y)[0].weight, 1.f);
            EXPECT_EQ(map.dominantPolicy(x, y).ray.shading.maxDepth, 3);
        }
    EXPECT_EQ(map.blendedPixelCount(), 0u);
}

TEST(PolicyMap, PixelsPointAtSharedEntries) {
    PolicyMap map(2, 2);
    PixelPolicy inner;
    inner.ray.query(RayType::Primary).layerMask = layerBit(1);
    inner.ray.query(RayType::Primary).tMin = 2.5f;
    const uint16_t id = map.addPolicy(inner);
    map.setPixel(1, 0, id);
    map.setPixel(0, 1, id);
    EXPECT_EQ(map.policies().size(), 2u);
    EXPECT_EQ(map.mixIndex(1, 0), map.mixIndex(0, 1));
    EXPECT_NE(map.mixIndex(1, 0), map.mixIndex(0, 0));
    EXPECT_EQ(map.dominantPolicy(1, 0).ray.query(RayType::Primary).layerMask, layerBit(1));
    EXPECT_EQ(map.dominantPolicy(0, 1).ray.query(RayType::Primary).tMin, 2.5f);
    EXPECT_EQ(map.dominantPolicy(0, 0).ray.query(RayType::Primary).layerMask, kAllLayers);
}

TEST(PolicyMap, BlendsAreNormalisedAndDropNonPositiveWeights) {
    PolicyMap map(3, 1);
    const uint16_t a = map.addPolicy(PixelPolicy{});
    const uint16_t b = map.addPolicy(PixelPolicy{});
    const std::vector<PolicyTerm> terms{{0, 1.f}, {a, 3.f}, {b, 0.f}};
    map.setPixelBlend(1, 0, terms);
    ASSERT_EQ(map.terms(1, 0).size(), 2u);
    EXPECT_FLOAT_EQ(map.terms(1, 0)[0].weight, 0.25f);
    EXPECT_FLOAT_EQ(map.terms(1, 0)[1].weight, 0.75f);
    EXPECT_EQ(&map.dominantPolicy(1, 0), &map.policy(a));
    EXPECT_EQ(map.blendedPixelCount(), 1u);

    // One positive term is a plain pixel, shared with every other pixel on that policy.
    const std::vector<PolicyTerm> single{{b, 0.5f}, {a, 0.f}};
    map.setPixelBlend(2, 0, single);
    map.setPixel(0, 0, b);
    EXPECT_EQ(map.mixIndex(2, 0), map.mixIndex(0, 0));
    EXPECT_EQ(map.blendedPixelCount(), 1u);
}

TEST(PolicyMap, RejectsBlendsWithoutWeightOrWithUnknownPolicies) {
    PolicyMap map(1, 1);
    const std::vector<PolicyTerm> zero{{0, 0.f}};
    EXPECT_THROW(map.setPixelBlend(0, 0, zero), Error);
    const std::vector<PolicyTerm> unknown{{0, 0.5f}, {7, 0.5f}};
    EXPECT_THROW(map.setPixelBlend(0, 0, unknown), Error);
}
