#include <mvcl/core/Error.h>
#include <mvcl/tracer/RayQuery.h>

#include <gtest/gtest.h>

#include <limits>

using namespace mvcl;

TEST(RayQuery, ClipVolumesComposeAsIntersectionOfConstraints) {
    RayQuery q;
    EXPECT_TRUE(q.acceptsPoint({100.f, 0.f, 0.f}));
    q.addClip(ClipVolume::box({-1.f, -1.f, -1.f}, {1.f, 1.f, 1.f}, ClipVolume::Keep::Outside)); // remove the unit box
    q.addClip(ClipVolume::sphere({0.f, 0.f, 0.f}, 3.f, ClipVolume::Keep::Inside)); // keep only the radius-3 ball
    EXPECT_FALSE(q.acceptsPoint({0.f, 0.f, 0.f}));   // cut away
    EXPECT_TRUE(q.acceptsPoint({2.f, 0.f, 0.f}));    // between box and ball
    EXPECT_FALSE(q.acceptsPoint({0.f, 3.5f, 0.f}));  // outside the ball
    q.addClip(ClipVolume::halfSpace({0.f, 1.f, 0.f}, 0.5f, ClipVolume::Keep::Inside)); // keep y ≥ 0.5 only
    EXPECT_FALSE(q.acceptsPoint({2.f, 0.f, 0.f}));
    EXPECT_TRUE(q.acceptsPoint({2.f, 1.f, 0.f}));
}

TEST(RayQuery, AddClipKeepsEqualVolumesOnceAndThrowsWhenFull) {
    RayQuery q;
    const ClipVolume ball = ClipVolume::sphere({0.f, 0.f, 0.f}, 1.f, ClipVolume::Keep::Outside);
    q.addClip(ball);
    q.addClip(ball);
    EXPECT_EQ(q.clipCount(), 1);
    for (int i = 1; i < kMaxClipVolumes; ++i) q.addClip(ClipVolume::sphere({0.f, 0.f, 0.f}, float(i + 1), ClipVolume::Keep::Outside));
    EXPECT_EQ(q.clipCount(), kMaxClipVolumes);
    const ClipVolume extra = ClipVolume::sphere({1.f, 0.f, 0.f}, 1.f, ClipVolume::Keep::Outside);
    EXPECT_FALSE(q.tryAddClip(extra));
    EXPECT_THROW(q.addClip(extra), Error);
    EXPECT_TRUE(q.tryAddClip(ball)); // already there: nothing to add
    EXPECT_EQ(q.clipCount(), kMaxClipVolumes);
}

TEST(RayQuery, ClipVolumeNamesWhatEachShapeStoresAndValidates) {
    const ClipVolume box = ClipVolume::box({0.f, 1.f, 2.f}, {3.f, 4.f, 5.f}, ClipVolume::Keep::Inside);
    EXPECT_EQ(box.boxMin(), glm::vec3(0.f, 1.f, 2.f));
    EXPECT_EQ(box.boxMax(), glm::vec3(3.f, 4.f, 5.f));
    EXPECT_TRUE(box.isValid());
    const ClipVolume ball = ClipVolume::sphere({1.f, 2.f, 3.f}, 4.f, ClipVolume::Keep::Outside);
    EXPECT_EQ(ball.center(), glm::vec3(1.f, 2.f, 3.f));
    EXPECT_EQ(ball.radius(), 4.f);
    const ClipVolume half = ClipVolume::halfSpace({0.f, 0.f, 2.f}, 1.f, ClipVolume::Keep::Inside);
    EXPECT_EQ(half.normal(), glm::vec3(0.f, 0.f, 2.f));
    EXPECT_EQ(half.offset(), 1.f);
    EXPECT_TRUE(half.contains({0.f, 0.f, 0.5f}));
    EXPECT_FALSE(half.contains({0.f, 0.f, 0.49f}));

    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(ClipVolume::box({1.f, 0.f, 0.f}, {0.f, 1.f, 1.f}, ClipVolume::Keep::Inside).isValid());
    EXPECT_FALSE(ClipVolume::sphere({0.f, 0.f, 0.f}, -1.f, ClipVolume::Keep::Inside).isValid());
    EXPECT_FALSE(ClipVolume::sphere({nan, 0.f, 0.f}, 1.f, ClipVolume::Keep::Inside).isValid());
    EXPECT_FALSE(ClipVolume::halfSpace({0.f, 0.f, 0.f}, 1.f, ClipVolume::Keep::Inside).isValid());
    EXPECT_FALSE(ClipVolume::halfSpace({0.f, 0.f, 1.f}, std::numeric_limits<float>::infinity(),
                                       ClipVolume::Keep::Inside).isValid());
}
