#include <mvcl/tracer/RayQuery.h>

#include <gtest/gtest.h>

using namespace mvcl;

TEST(RayQuery, ClipVolumesComposeAsIntersectionOfConstraints) {
    RayQuery q;
    EXPECT_TRUE(q.acceptsPoint({100.f, 0.f, 0.f}));
    ClipVolume cut; // remove the unit box
    cut.shape = ClipVolume::Shape::Box;
    cut.keep = ClipVolume::Keep::Outside;
    cut.a = {-1.f, -1.f, -1.f};
    cut.b = {1.f, 1.f, 1.f};
    ClipVolume ball; // keep only the radius-3 ball
    ball.shape = ClipVolume::Shape::Sphere;
    ball.keep = ClipVolume::Keep::Inside;
    ball.radius = 3.f;
    q.clips[q.clipCount++] = cut;
    q.clips[q.clipCount++] = ball;
    EXPECT_FALSE(q.acceptsPoint({0.f, 0.f, 0.f}));   // cut away
    EXPECT_TRUE(q.acceptsPoint({2.f, 0.f, 0.f}));    // between box and ball
    EXPECT_FALSE(q.acceptsPoint({0.f, 3.5f, 0.f}));  // outside the ball
    ClipVolume half; // keep y ≥ 0.5 only
    half.shape = ClipVolume::Shape::HalfSpace;
    half.keep = ClipVolume::Keep::Inside;
    half.a = {0.f, 1.f, 0.f};
    half.radius = 0.5f;
    q.clips[q.clipCount++] = half;
    EXPECT_FALSE(q.acceptsPoint({2.f, 0.f, 0.f}));
    EXPECT_TRUE(q.acceptsPoint({2.f, 1.f, 0.f}));
}
