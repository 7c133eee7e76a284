// AnimationPlayer: a frame's lens values committed on the view's own lenses (only those that
// change), the camera in scene space, and the lenses put back afterwards.

#include <mvcl/controller/AnimationPlayer.h>

#include <mvcl/io/AnimationFile.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/lens/Lens.h>
#include <mvcl/lens/LensRegistry.h>

#include "lens/InTreeLensRegistry.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

using namespace mvcl;

namespace {

const LensRegistry &registry() {
    EXPECT_TRUE(test::inTreeLenses().loadErrors.empty()) << test::inTreeLenses().loadErrors.front().what();
    return test::inTreeLenses().registry;
}

LensStack twoLenses() {
    return parseLensStackJson(R"({"lenses": [{"type": "layer", "label": "reveal"},
                                             {"type": "achromatic", "label": "grey"}]})",
                              "stack.json", registry())
        .lenses;
}

/// A scene whose world origin is far from zero: world ↔ scene conversions round in float.
const ViewCoordinates kCoordinates({64, 48}, glm::dvec3(1000.3, -20.7, 5.1));

} // namespace

TEST(AnimationPlayer, CommitsTheKeyedValuesOfChangedLensesOnly) {
    const LensStack lenses = twoLenses();
    Animation animation;
    animation.setFrameRate(4.0);
    animation.setDuration(1.0);
    animation.addSweep(0, "distance", PropertyValue::real(0.0), PropertyValue::real(3.0));
    const Camera camera = Camera::lookAt({0.f, 0.f, 5.f}, glm::vec3(0.f), {0.f, 1.f, 0.f}, 40.f);
    AnimationPlayer player(animation, lenses, camera, kCoordinates);
    const auto grey = lenses.lens(1)->snapshot();
    const uint64_t revealVersion = lenses.lens(0)->snapshot()->version;

    player.showFrame(0); // distance 0 is the lens's value already: nothing to commit
    EXPECT_EQ(lenses.lens(0)->snapshot()->version, revealVersion);
    player.showFrame(2);
    EXPECT_EQ(lenses.lens(0)->committedValues()[1].toReal(), 2.0);
    EXPECT_GT(lenses.lens(0)->snapshot()->version, revealVersion);
    EXPECT_EQ(lenses.lens(1)->snapshot(), grey); // not animated: the same snapshot
    player.showFrame(3);
    EXPECT_EQ(lenses.lens(0)->committedValues()[1].toReal(), 3.0);

    player.restoreLenses();
    EXPECT_EQ(lenses.lens(0)->committedValues()[1].toReal(), 0.0);
}

TEST(AnimationPlayer, ACameraNoKeyframeMovesIsTheBaseCameraItself) {
    const LensStack lenses = twoLenses();
    Animation animation;
    animation.addSweep(1, "amount", PropertyValue::real(0.0), PropertyValue::real(1.0));
    const Camera camera = Camera::lookAt({0.1f, 0.2f, 5.3f}, {0.01f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 33.f);
    AnimationPlayer player(animation, lenses, camera, kCoordinates);
    for (int frame = 0; frame < animation.frameCount(); frame += 7) EXPECT_EQ(player.showFrame(frame), camera);
}

TEST(AnimationPlayer, CamerasComeBackInSceneSpace) {
    const LensStack lenses = twoLenses();
    const Animation turntable = Animation::turntable(4, 1.0);
    const Camera camera = Camera::lookAt({0.f, 0.f, 5.f}, glm::vec3(0.f), {0.f, 1.f, 0.f}, 40.f);
    AnimationPlayer player(turntable, lenses, camera, kCoordinates);
    const Camera quarter = player.showFrame(1); // 90 degrees about +y through the target
    EXPECT_NEAR(quarter.eye().x, 5.f, 1e-3f);
    EXPECT_NEAR(quarter.eye().z, 0.f, 1e-3f);
    EXPECT_NEAR(glm::distance(quarter.target(), camera.target()), 0.f, 1e-3f);
    EXPECT_EQ(player.cameraAt(turntable.frameTime(1)), quarter);
}

TEST(AnimationPlayer, ShowsRegionsAndEnabledFlags) {
    const LensStack lenses = twoLenses();
    const Animation animation = parseAnimationJson(R"({"duration": 2, "frameRate": 1,
        "lenses": [{"lens": "grey", "keyframes": [{"time": 0, "region": {"center": [0.2, 0.5]}, "enabled": true},
                                                  {"time": 1, "region": {"center": [0.6, 0.5]}, "enabled": false}]}]})",
                                                   "anim.json", lenses);
    AnimationPlayer player(animation, lenses, Camera(), kCoordinates);
    player.showTime(0.5);
    EXPECT_FLOAT_EQ(lenses.lens(1)->snapshot()->region.center().x, 0.4f);
    EXPECT_TRUE(lenses.lens(1)->snapshot()->enabled);
    player.showFrame(1);
    EXPECT_FALSE(lenses.lens(1)->snapshot()->enabled);
}
