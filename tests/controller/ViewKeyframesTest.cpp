// Keyframes taken from a view (its camera, a lens as committed) play the view back as it was,
// through the animation file format as the viewer saves it.

#include <mvcl/controller/ViewKeyframes.h>

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

} // namespace

TEST(ViewKeyframes, KeyframesOfAViewPlayItBack) {
    const LensStack lenses =
        parseLensStackJson(R"({"lenses": [{"type": "shadow", "label": "s", "region": {"center": [0.3, 0.4]}}]})",
                           "stack.json", registry())
            .lenses;
    const ViewCoordinates coordinates({64, 48}, glm::dvec3(10.0, 0.0, 0.0));
    const Camera first = Camera::lookAt({0.f, 1.f, 6.f}, glm::vec3(0.f), {0.f, 1.f, 0.f}, 40.f);
    const Camera second = Camera::lookAt({4.f, 1.f, 2.f}, glm::vec3(0.f), {0.f, 1.f, 0.f}, 30.f);
    Lens &lens = *lenses.lens(0);

    Animation animation;
    animation.setDuration(2.0);
    animation.addCameraKeyframe(cameraKeyframeOf(first, coordinates, 0.0));
    animation.addLensKeyframe(0, lensKeyframeOf(lens, 0.0));
    lens.setPropertyText("strength", "0.2");
    lens.setPropertyText("mode", "tinted");
    LensRegion moved = lens.region();
    moved.setCenter({0.7f, 0.4f});
    lens.setRegion(moved);
    lens.commit();
    animation.addCameraKeyframe(cameraKeyframeOf(second, coordinates, 2.0));
    animation.addLensKeyframe(0, lensKeyframeOf(lens, 2.0));
    // Through the file format, as the viewer saves it.
    const Animation saved = parseAnimationJson(animationJson(animation, lenses), "anim.json", lenses);

    AnimationPlayer player(saved, lenses, first, coordinates);
    const Camera start = player.showTime(0.0);
    EXPECT_NEAR(glm::distance(start.eye(), first.eye()), 0.f, 1e-5f);
    EXPECT_EQ(lens.property("strength").toReal(), 1.0); // as it was
    EXPECT_EQ(lens.property("mode").toChoice(), "on");
    const Camera middle = player.showTime(1.0);
    EXPECT_NEAR(middle.verticalFovDegrees(), 35.f, 1e-4f);
    EXPECT_NEAR(lens.property("strength").toReal(), 0.6, 1e-9);
    EXPECT_NEAR(lens.snapshot()->region.center().x, 0.5f, 1e-6f);
    EXPECT_EQ(lens.property("mode").toChoice(), "on"); // a choice steps at the later keyframe
    player.showTime(2.0);
    EXPECT_EQ(lens.property("mode").toChoice(), "tinted");
}
