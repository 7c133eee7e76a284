// ViewRouter: which view an event goes to, in which of its pixels; capture and focus.

#include <mvcl/controller/ViewRouter.h>

#include <gtest/gtest.h>

namespace mvcl::test {
namespace {

ViewRouter twoByTwo() {
    ViewRouter router;
    router.setViewRects({{0, {0, 0}, {100, 50}}, {1, {100, 0}, {100, 50}}, {2, {0, 50}, {100, 50}}, {3, {100, 50}, {100, 50}}});
    return router;
}

TEST(ViewRouterTest, PointerEventsGoToTheViewUnderThePointerInItsOwnPixels) {
    ViewRouter router = twoByTwo();
    const ViewRouter::Routed routed = router.route(InputEvent::pointerMove({130.f, 70.f}));
    EXPECT_EQ(routed.view, 3);
    EXPECT_EQ(routed.event.position, glm::vec2(30.f, 20.f));
    EXPECT_EQ(router.route(InputEvent::scrolled({10.f, 60.f}, {0.f, 1.f})).view, 2);
    EXPECT_EQ(router.route(InputEvent::pointerMove({250.f, 10.f})).view, -1); // outside every view
    EXPECT_EQ(router.route(InputEvent::pointerPress({250.f, 10.f}, PointerButton::Left)).view, -1);
    EXPECT_EQ(router.focus(), 0); // a press outside focuses nothing
}

TEST(ViewRouterTest, APressCapturesThePointerUntilItsReleaseAndFocusesTheView) {
    ViewRouter router = twoByTwo();
    EXPECT_EQ(router.route(InputEvent::pointerPress({150.f, 10.f}, PointerButton::Left)).view, 1);
    EXPECT_EQ(router.focus(), 1);
    EXPECT_EQ(router.capture(), 1);
    const ViewRouter::Routed outside = router.route(InputEvent::pointerMove({20.f, 80.f}));
    EXPECT_EQ(outside.view, 1);
    EXPECT_EQ(outside.event.position, glm::vec2(-80.f, 80.f));
    // A second button while the first is down stays with the view, and the release of both ends it.
    EXPECT_EQ(router.route(InputEvent::pointerPress({20.f, 80.f}, PointerButton::Middle)).view, 1);
    EXPECT_EQ(router.route(InputEvent::pointerRelease({20.f, 80.f}, PointerButton::Middle)).view, 1);
    EXPECT_EQ(router.capture(), 1);
    EXPECT_EQ(router.route(InputEvent::pointerRelease({20.f, 80.f}, PointerButton::Left)).view, 1);
    EXPECT_EQ(router.capture(), -1);
    EXPECT_EQ(router.route(InputEvent::pointerMove({20.f, 80.f})).view, 2);
    EXPECT_EQ(router.route(InputEvent::pointerRelease({20.f, 80.f}, PointerButton::Left)).view, -1);
}

TEST(ViewRouterTest, KeysAndDropsGoToTheFocusedView) {
    ViewRouter router = twoByTwo();
    router.setFocus(2);
    EXPECT_EQ(router.route(InputEvent::keyPress(Key::F)).view, 2);
    EXPECT_EQ(router.route(InputEvent::fileDrop({150.f, 10.f}, {"a.json"})).view, 2);
    EXPECT_EQ(router.route(InputEvent::resized({200, 100})).view, -1);
}

TEST(ViewRouterTest, ACapturedViewThatGoesAwayReleasesTheCapture) {
    ViewRouter router = twoByTwo();
    router.route(InputEvent::pointerPress({150.f, 70.f}, PointerButton::Left));
    ASSERT_EQ(router.capture(), 3);
    router.setViewRects({{0, {0, 0}, {200, 100}}});
    EXPECT_EQ(router.capture(), -1);
    EXPECT_EQ(router.route(InputEvent::pointerMove({150.f, 70.f})).view, 0);
}

} // namespace
} // namespace mvcl::test
