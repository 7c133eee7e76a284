// Controller camera input: orbit keeps the distance to the centre, pan moves eye and target
// together, zoom keeps the point under the cursor in place, frame-all and preset views.

#include "controller/ControllerFixture.h"

#include <mvcl/controller/CameraNavigation.h>

#include <glm/geometric.hpp>

namespace mvcl::test {
namespace {

class ControllerCameraTest : public ControllerFixture {};

float distanceToTarget(const Camera &camera) { return glm::length(camera.eye() - camera.target()); }

TEST_F(ControllerCameraTest, LeftDragOnTheEmptyImageOrbitsAboutTheTarget) {
    auto controller = makeController();
    const Camera before = controller->camera();
    drag(*controller, {5.f, 5.f}, {45.f, 25.f});
    const Camera after = controller->camera();
    EXPECT_NE(after.eye(), before.eye());
    EXPECT_EQ(after.target(), before.target());
    EXPECT_NEAR(distanceToTarget(after), distanceToTarget(before), 1e-5f * distanceToTarget(before));
    EXPECT_EQ(controller->undoCount(), 1);
    controller->undo();
    EXPECT_EQ(controller->camera(), before);
}

TEST_F(ControllerCameraTest, OrbitDirectionsFollowThePointer) {
    const Camera front = Camera::lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    // Dragging right turns the scene right: the eye goes left (−x) around the target.
    EXPECT_LT(orbitCamera(front, -0.3f, 0.f).eye().x, 0.f);
    // A positive pitch raises the eye.
    EXPECT_GT(orbitCamera(front, 0.f, 0.3f).eye().y, 0.f);
    // Past the pole the pitch stops: the eye stays on the near side of the up axis.
    const Camera over = orbitCamera(front, 0.f, 3.f);
    EXPECT_GT(over.eye().z, 0.f);
    EXPECT_NEAR(glm::length(over.eye()), 5.f, 1e-4f);
}

TEST_F(ControllerCameraTest, MiddleDragAndShiftLeftDragPanEyeAndTargetTogether) {
    for (const auto &[button, modifiers] : {std::pair{PointerButton::Middle, KeyModifier::None},
                                            std::pair{PointerButton::Left, KeyModifier::Shift}}) {
        auto controller = makeController();
        controller->addLens("layer", {0.5f, 0.5f}); // a pan starts on a lens too
        const Camera before = controller->camera();
        const glm::vec2 from{80.f, 60.f}, to{100.f, 50.f};
        drag(*controller, from, to, button, modifiers);
        const Camera after = controller->camera();
        const glm::vec3 eyeMove = after.eye() - before.eye();
        const glm::vec3 targetMove = after.target() - before.target();
        EXPECT_GT(glm::length(eyeMove), 0.f);
        EXPECT_NEAR(glm::length(eyeMove - targetMove), 0.f, 1e-5f);
        // The target (at the view centre) follows the pointer: it appears 20 px right, 10 px up.
        const glm::vec2 seen = projectToPixel(after, before.target(), kWidth, kHeight);
        EXPECT_NEAR(seen.x, 80.f + 20.f, 0.01f);
        EXPECT_NEAR(seen.y, 60.f - 10.f, 0.01f);
        EXPECT_EQ(controller->lensStack().lens(0)->snapshot()->region.center(), glm::vec2(0.5f)) << "lens not moved";
    }
}

TEST_F(ControllerCameraTest, ScrollZoomsTowardThePointUnderTheCursor) {
    auto controller = makeController();
    const Camera before = controller->camera();
    const glm::vec2 cursor{60.f, 70.f};
    const glm::vec3 underCursor = controller->pointUnder(cursor);
    const glm::vec3 elsewhere = controller->pointUnder({140.f, 20.f});
    ASSERT_NEAR(glm::length(projectToPixel(before, underCursor, kWidth, kHeight) - cursor), 0.f, 0.01f);

    controller->handle(InputEvent::scrolled(cursor, {0.f, 2.f}));
    const Camera after = controller->camera();
    EXPECT_LT(distanceToTarget(after), distanceToTarget(before)) << "scrolling up zooms in";
    const float cursorShift = glm::length(projectToPixel(after, underCursor, kWidth, kHeight) - cursor);
    const float elsewhereShift = glm::length(projectToPixel(after, elsewhere, kWidth, kHeight) -
                                             projectToPixel(before, elsewhere, kWidth, kHeight));
    EXPECT_LT(cursorShift, 0.05f);
    EXPECT_GT(elsewhereShift, 5.f);
    EXPECT_LT(cursorShift, elsewhereShift);

    controller->handle(InputEvent::scrolled(cursor, {0.f, 1.f}));
    controller->handle(InputEvent::scrolled(cursor, {0.f, -0.5f}));
    EXPECT_EQ(controller->undoCount(), 1) << "a run of scroll steps is one undo step";
    controller->undo();
    EXPECT_EQ(controller->camera(), before);
}

TEST_F(ControllerCameraTest, PresetKeysLookAlongTheAxesAndFrameTheScene) {
    auto controller = makeController();
    press(*controller, Key::Digit1);
    Camera camera = controller->camera();
    EXPECT_FLOAT_EQ(camera.eye().x, camera.target().x);
    EXPECT_GT(camera.eye().z, camera.target().z) << "front: from +z";
    press(*controller, Key::Keypad3, KeyModifier::Control);
    camera = controller->camera();
    EXPECT_LT(camera.eye().x, camera.target().x) << "Ctrl + keypad 3: from the left";
    press(*controller, Key::Digit5);
    camera = controller->camera();
    EXPECT_GT(camera.eye().y, camera.target().y) << "top: from +y";
    EXPECT_FLOAT_EQ(camera.eye().x, camera.target().x);
    EXPECT_FLOAT_EQ(camera.eye().z, camera.target().z);
    // Every corner of the scene's box is in the image.
    const Bounds3f bounds = controller->scene().bounds();
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec2 pixel = projectToPixel(camera, corner, kWidth, kHeight);
        EXPECT_GE(pixel.x, 0.f);
        EXPECT_LE(pixel.x, float(kWidth));
        EXPECT_GE(pixel.y, 0.f);
        EXPECT_LE(pixel.y, float(kHeight));
    }
    EXPECT_EQ(controller->undoCount(), 3);
}

TEST_F(ControllerCameraTest, FrameAllKeepsTheViewDirection) {
    auto controller = makeController();
    controller->orbit(0.7f, 0.2f);
    controller->zoomAt({80.f, 60.f}, 0.2f);
    const Camera zoomedIn = controller->camera();
    press(*controller, Key::F);
    const Camera framed = controller->camera();
    const glm::vec3 before = glm::normalize(zoomedIn.target() - zoomedIn.eye());
    const glm::vec3 after = glm::normalize(framed.target() - framed.eye());
    EXPECT_NEAR(glm::dot(before, after), 1.f, 1e-5f);
    EXPECT_GT(distanceToTarget(framed), distanceToTarget(zoomedIn));
    EXPECT_EQ(framed.target(), controller->scene().bounds().center());
}

TEST_F(ControllerCameraTest, ResizeRendersAtTheNewFramebufferSize) {
    auto controller = makeController();
    controller->handle(InputEvent::resized({320, 200}, 2.f));
    EXPECT_EQ(controller->viewSize(), glm::ivec2(320, 200));
    EXPECT_EQ(controller->contentScale(), 2.f);
    EXPECT_EQ(controller->renderSettings().width, 320);
    EXPECT_EQ(controller->renderSession().settings().height, 200);
    EXPECT_EQ(controller->undoCount(), 0) << "a resize is not an edit";
}

} // namespace
} // namespace mvcl::test
