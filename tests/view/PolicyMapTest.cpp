#include <mvcl/view/PolicyMap.h>

#include <gtest/gtest.h>

using namespace mvcl;

TEST(PolicyMap, EveryPixelStartsOnTheBasePolicy) {
    RayPolicy base;
    base.shading.maxDepth = 3;
    const PolicyMap map(4, 3, base);
    ASSERT_EQ(map.policies().size(), 1u);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            EXPECT_EQ(map.pixel(x, y), 0);
            EXPECT_EQ(map.policyAt(x, y).shading.maxDepth, 3);
        }
}

TEST(PolicyMap, PixelsPointAtSharedEntries) {
    PolicyMap map(2, 2);
    RayPolicy inner;
    inner.query(RayType::Primary).layerMask = layerBit(1);
    inner.query(RayType::Primary).tMin = 2.5f;
    const uint16_t id = map.addPolicy(inner);
    map.setPixel(1, 0, id);
    map.setPixel(0, 1, id);
    EXPECT_EQ(map.policies().size(), 2u);
    EXPECT_EQ(map.policyAt(1, 0).query(RayType::Primary).layerMask, layerBit(1));
    EXPECT_EQ(map.policyAt(0, 1).query(RayType::Primary).tMin, 2.5f);
    EXPECT_EQ(map.policyAt(0, 0).query(RayType::Primary).layerMask, kAllLayers);
    EXPECT_EQ(map.policyAt(1, 1).query(RayType::Shadow).layerMask, kAllLayers);
}
