// First crossings of `mvcl-bench convergence`.

#include "ConvergenceCurves.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace mvcl::bench;

TEST(ConvergenceCurves, CrossingIsInterpolatedLogLog) {
    // error = 1 / seconds: a straight line in log-log, so the interpolation is exact.
    const Curve curve{{1.0, 1.0}, {10.0, 0.1}, {100.0, 0.01}};
    const auto c = firstCrossing(curve, 0.05);
    ASSERT_TRUE(c);
    EXPECT_FALSE(c->atFirstPoint);
    EXPECT_NEAR(c->seconds, 20.0, 1e-9);
    EXPECT_NEAR(firstCrossing(curve, 0.1)->seconds, 10.0, 1e-9); // reaching = at or below
}

TEST(ConvergenceCurves, FirstCrossingIgnoresLaterRises) {
    const Curve curve{{1.0, 1.0}, {2.0, 0.25}, {4.0, 0.5}, {8.0, 0.1}};
    EXPECT_NEAR(firstCrossing(curve, 0.5)->seconds, std::sqrt(2.0), 1e-9);
}

TEST(ConvergenceCurves, NeverReachedOrReachedAtOnce) {
    const Curve curve{{1.0, 1.0}, {2.0, 0.5}};
    EXPECT_FALSE(firstCrossing(curve, 0.4).has_value());
    const auto first = firstCrossing(curve, 2.0);
    ASSERT_TRUE(first);
    EXPECT_TRUE(first->atFirstPoint);
    EXPECT_DOUBLE_EQ(first->seconds, 1.0);
}

TEST(ConvergenceCurves, ZeroErrorFallsBackToLinearInterpolation) {
    const auto c = firstCrossing({{1.0, 1.0}, {3.0, 0.0}}, 0.5);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->seconds, 2.0, 1e-12);
}
