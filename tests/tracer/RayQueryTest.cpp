#include <mvcl/core/Error.h>
#include <mvcl/tracer/RayQuery.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace mvcl;

TEST(RayQuery, ClipVolumesComposeAsIntersectionOfConstraints) {
    RayQuery q;
    EXPECT_TRUE(q.acceptsPoint({100.f, 0.f, 0.f}, 0));
    q.addClip(ClipVolume::box({-1.f, -1.f, -1.f}, {1.f, 1.f, 1.f}, ClipVolume::Keep::Outside)); // remove the unit box
    q.addClip(ClipVolume::sphere({0.f, 0.f, 0.f}, 3.f, ClipVolume::Keep::Inside)); // keep only the radius-3 ball
    EXPECT_FALSE(q.acceptsPoint({0.f, 0.f, 0.f}, 0));   // cut away
    EXPECT_TRUE(q.acceptsPoint({2.f, 0.f, 0.f}, 0));    // between box and ball
    EXPECT_FALSE(q.acceptsPoint({0.f, 3.5f, 0.f}, 0));  // outside the ball
    q.addClip(ClipVolume::halfSpace({0.f, 1.f, 0.f}, 0.5f, ClipVolume::Keep::Inside)); // keep y ≥ 0.5 only
    EXPECT_FALSE(q.acceptsPoint({2.f, 0.f, 0.f}, 0));
    EXPECT_TRUE(q.acceptsPoint({2.f, 1.f, 0.f}, 0));
}

TEST(RayQuery, AVolumeActsOnlyOnItsLayers) {
    ClipVolume cut = ClipVolume::sphere({0.f, 0.f, 0.f}, 1.f, ClipVolume::Keep::Outside);
    cut.setLayerMask(layerBit(0) | layerBit(2));
    RayQuery q;
    q.addClip(cut);
    EXPECT_FALSE(q.acceptsPoint({0.f, 0.f, 0.f}, 0));
    EXPECT_TRUE(q.acceptsPoint({0.f, 0.f, 0.f}, 1)) << "layer 1 is spared";
    EXPECT_FALSE(q.acceptsPoint({0.f, 0.f, 0.f}, 2));
    EXPECT_TRUE(q.acceptsPoint({2.f, 0.f, 0.f}, 0));
}

TEST(RayQuery, AnOrientedBoxContainsWhatItsTurnedSidesEnclose) {
    // A unit-half box turned 45° about z at (5, 0, 0): its corners reach along the diagonals.
    const float h = std::sqrt(0.5f);
    const glm::mat3 axes({h, h, 0.f}, {-h, h, 0.f}, {0.f, 0.f, 1.f});
    const ClipVolume box = ClipVolume::orientedBox({5.f, 0.f, 0.f}, {1.f, 1.f, 1.f}, axes, ClipVolume::Keep::Outside);
    EXPECT_TRUE(box.isOriented());
    EXPECT_TRUE(box.isValid());
    EXPECT_TRUE(box.contains({5.f, 1.3f, 0.f}));  // along the turned diagonal: inside (≤ √2)
    EXPECT_FALSE(box.contains({5.9f, 0.9f, 0.f})); // an axis-aligned box would hold this
    EXPECT_TRUE(box.contains({5.f, 0.f, 0.99f}));
    EXPECT_FALSE(box.contains({5.f, 0.f, 1.01f}));
    // Not turned: the plain box, equal to the one box() makes.
    EXPECT_EQ(ClipVolume::orientedBox({1.f, 2.f, 3.f}, {0.5f, 0.5f, 0.5f}, glm::mat3(1.f), ClipVolume::Keep::Inside),
              ClipVolume::box({0.5f, 1.5f, 2.5f}, {1.5f, 2.5f, 3.5f}, ClipVolume::Keep::Inside));
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
