// ConvergenceHistory: one point per pass with an estimate, a new curve after a restart, and the
// resampling onto an even time axis that the viewer's live curve draws.

#include <mvcl/view/ConvergenceHistory.h>

#include <gtest/gtest.h>

#include <cmath>

namespace mvcl {
namespace {

ConvergenceStats at(double seconds, std::optional<double> relativeMse) {
    ConvergenceStats c;
    c.elapsedSeconds = seconds;
    c.estimatedRelativeMse = relativeMse;
    return c;
}

TEST(ConvergenceHistory, KeepsOnePointPerPassWithAnEstimate) {
    ConvergenceHistory h;
    h.add(at(0.1, std::nullopt), 1); // one sample a pixel: no estimate yet
    EXPECT_TRUE(h.isEmpty());
    h.add(at(0.2, 1e-2), 2);
    h.add(at(0.2, 1e-2), 2); // the same pass seen by two UI frames
    h.add(at(0.4, 1e-3), 3);
    ASSERT_EQ(h.points().size(), 2u);
    EXPECT_DOUBLE_EQ(h.points()[1].seconds, 0.4);
    EXPECT_DOUBLE_EQ(h.points()[1].relativeMse, 1e-3);
}

TEST(ConvergenceHistory, StartsOverWhenTheSessionRestarts) {
    ConvergenceHistory h;
    h.add(at(0.5, 1e-2), 1);
    h.add(at(1.0, 1e-3), 2);
    h.add(at(0.05, 2e-2), 3); // the camera moved: time since the restart went back
    ASSERT_EQ(h.points().size(), 1u);
    EXPECT_DOUBLE_EQ(h.points()[0].relativeMse, 2e-2);
    h.clear();
    EXPECT_TRUE(h.isEmpty());
}

TEST(ConvergenceHistory, ResamplesTheCurveOntoEvenTimes) {
    ConvergenceHistory h;
    EXPECT_TRUE(h.log10ErrorOverTime(8).empty());
    h.add(at(0.5, 1e-1), 1);
    h.add(at(1.0, 1e-2), 2);
    h.add(at(4.0, 1e-4), 3);
    EXPECT_TRUE(h.log10ErrorOverTime(1).empty());
    const std::vector<float> v = h.log10ErrorOverTime(5); // t = 0, 1, 2, 3, 4
    ASSERT_EQ(v.size(), 5u);
    EXPECT_FLOAT_EQ(v[0], -1.f); // before the first point: the first point's error
    EXPECT_FLOAT_EQ(v[1], -2.f);
    EXPECT_FLOAT_EQ(v[2], -2.f); // held until the next pass
    EXPECT_FLOAT_EQ(v[3], -2.f);
    EXPECT_FLOAT_EQ(v[4], -4.f);
}

} // namespace
} // namespace mvcl
