#include <mvcl/core/FloatBits.h>

#include <mvcl/core/Bounds3.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace mvcl;

TEST(FloatBits, NextFloatStepsExactlyOneUlpAcrossZeroAndInfinity) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (float v : {-1e30f, -1.f, -1e-40f, 0.f, -0.f, 1e-40f, 1.f, 3.5e7f, 1e30f}) {
        EXPECT_EQ(nextFloatUp(v), std::nextafter(v == 0.f ? 0.f : v, inf)) << v;
        EXPECT_EQ(nextFloatDown(v), std::nextafter(v == 0.f ? -0.f : v, -inf)) << v;
    }
    EXPECT_EQ(nextFloatUp(inf), inf);
    EXPECT_EQ(nextFloatDown(-inf), -inf);
}

TEST(FloatBits, GammaBoundsNOperations) {
    EXPECT_GT(gamma(1), kMachineEpsilon);
    EXPECT_LT(gamma(1), 1.0001f * kMachineEpsilon);
    EXPECT_GT(gamma(7), 7.f * kMachineEpsilon);
    EXPECT_LT(gamma(3), gamma(7));
}

TEST(Bounds3, EmptyBoxesExpandAndMeasure) {
    Bounds3f b;
    EXPECT_TRUE(b.isEmpty());
    EXPECT_EQ(b.area(), 0.f);
    b.expand({1.f, 2.f, 3.f});
    EXPECT_FALSE(b.isEmpty());
    b.expand({-1.f, 0.f, 3.f});
    EXPECT_EQ(b.extent(), glm::vec3(2.f, 2.f, 0.f));
    EXPECT_EQ(b.longestAxis(), 0);
    EXPECT_FLOAT_EQ(b.area(), 8.f);
    EXPECT_TRUE(b.contains({0.f, 1.f, 3.f}));
    EXPECT_FALSE(b.contains({0.f, 1.f, 3.5f}));
}
