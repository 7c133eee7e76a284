// Controller undo/redo: every edit is one step, undo and redo restore the exact state, key
// bindings, edit groups.

#include "controller/ControllerFixture.h"

#include <vector>

namespace mvcl::test {
namespace {

class ControllerHistoryTest : public ControllerFixture {};

TEST_F(ControllerHistoryTest, UndoAndRedoWalkThroughEveryStateExactly) {
    auto controller = makeController();
    std::vector<SessionState> states{controller->state()};
    const auto record = [&] { states.push_back(controller->state()); };

    controller->addLens("layer", {0.4f, 0.5f});
    record();
    drag(*controller, pixelOf({0.4f, 0.5f}), pixelOf({0.4f, 0.5f}) + glm::vec2(12.f, -6.f));
    record();
    controller->setLensProperty(0, "layers", "2-");
    record();
    controller->addLens("shadow", {0.6f, 0.5f});
    record();
    controller->setLensProperty(1, "mode", "tinted");
    record();
    controller->setLayerVisibility(1, LayerVisibility::Hidden);
    record();
    drag(*controller, {3.f, 3.f}, {40.f, 30.f}); // orbit
    record();
    controller->handle(InputEvent::scrolled({70.f, 60.f}, {0.f, 1.f}));
    record();
    controller->moveLens(1, 0);
    record();
    press(*controller, Key::E); // the selected lens: the shadow lens, now at 0
    record();
    controller->removeLens(1);
    record();
    controller->setLensRegion(0, LensRegion::polygon({{0.1f, 0.1f}, {0.5f, 0.1f}, {0.3f, 0.4f}}));
    record();

    const int steps = int(states.size()) - 1;
    ASSERT_EQ(controller->undoCount(), steps);
    for (int i = steps - 1; i >= 0; --i) {
        ASSERT_TRUE(controller->canUndo());
        controller->undo();
        EXPECT_EQ(controller->state(), states[std::size_t(i)]) << "after undoing step " << i + 1;
    }
    EXPECT_FALSE(controller->canUndo());
    for (int i = 1; i <= steps; ++i) {
        ASSERT_TRUE(controller->canRedo());
        controller->redo();
        EXPECT_EQ(controller->state(), states[std::size_t(i)]) << "after redoing step " << i;
    }
    EXPECT_FALSE(controller->canRedo());
}

TEST_F(ControllerHistoryTest, ControlZUndoesAndControlShiftZOrControlYRedoes) {
    auto controller = makeController();
    const SessionState empty = controller->state();
    controller->addLens("achromatic", {0.5f, 0.5f});
    const SessionState withLens = controller->state();
    press(*controller, Key::Z, KeyModifier::Control);
    EXPECT_EQ(controller->state(), empty);
    press(*controller, Key::Z, KeyModifier::Control | KeyModifier::Shift);
    EXPECT_EQ(controller->state(), withLens);
    press(*controller, Key::Z, KeyModifier::Control);
    press(*controller, Key::Y, KeyModifier::Control);
    EXPECT_EQ(controller->state(), withLens);
    press(*controller, Key::Z); // without Ctrl: nothing
    EXPECT_EQ(controller->state(), withLens);
}

TEST_F(ControllerHistoryTest, ANewEditDropsTheRedoSteps) {
    auto controller = makeController();
    controller->addLens("layer", {0.5f, 0.5f});
    controller->undo();
    ASSERT_TRUE(controller->canRedo());
    controller->addLens("shadow", {0.5f, 0.5f});
    EXPECT_FALSE(controller->canRedo());
}

TEST_F(ControllerHistoryTest, AnEditStepGroupsEditsAndAnEditThatChangesNothingIsNoStep) {
    auto controller = makeController();
    const int index = controller->addLens("achromatic", {0.5f, 0.5f});
    const SessionState before = controller->state();
    controller->beginEditStep(); // e.g. a slider dragged in a panel
    for (const char *amount : {"0.2", "0.4", "0.6"}) controller->setLensProperty(index, "amount", amount);
    EXPECT_FALSE(controller->canUndo()) << "no undo in the middle of a step";
    controller->endEditStep();
    EXPECT_EQ(controller->undoCount(), 2);
    controller->undo();
    EXPECT_EQ(controller->state(), before);

    const int steps = controller->undoCount();
    controller->setLensProperty(index, "amount", controller->lensProperty(index, "amount"));
    controller->setLayerVisibility(3, LayerVisibility::Visible);
    drag(*controller, {80.f, 60.f}, {80.f, 60.f}); // a click
    EXPECT_EQ(controller->undoCount(), steps);
}

TEST_F(ControllerHistoryTest, LayerVisibilitySetsThePrimaryLayerMaskOfTheBasePolicy) {
    auto controller = makeController();
    controller->setLayerVisibility(0, LayerVisibility::Hidden);
    EXPECT_EQ(controller->basePolicy().query(RayType::Primary).layerMask, kAllLayers & ~1u);
    EXPECT_EQ(controller->basePolicy().query(RayType::Shadow).layerMask, kAllLayers);
    EXPECT_EQ(controller->layerVisibility(0), LayerVisibility::Hidden);
    EXPECT_EQ(controller->layerVisibility(1), LayerVisibility::Visible);
    EXPECT_THROW(controller->setLayerVisibility(32, LayerVisibility::Hidden), Error);
    controller->undo();
    EXPECT_EQ(controller->visibleLayers(), kAllLayers);
}

} // namespace
} // namespace mvcl::test
