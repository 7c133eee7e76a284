// Controller lens edits from synthetic input: drag, resize by corner, edge and polygon vertex,
// reorder, enable/disable, duplicate/delete, add every registered type, property edits.

#include <mvcl/testing/ErrorOf.h>
#include "controller/ControllerFixture.h"

#include <mvcl/view/RenderSession.h>

namespace mvcl::test {
namespace {

class ControllerLensEditTest : public ControllerFixture {};

void expectVec2Eq(const glm::vec2 &actual, const glm::vec2 &expected) {
    EXPECT_FLOAT_EQ(actual.x, expected.x);
    EXPECT_FLOAT_EQ(actual.y, expected.y);
}

TEST_F(ControllerLensEditTest, DragMovesTheLensByThePointerDeltaInOneUndoStep) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.5f, 0.5f});
    const LensRegion before = controller->lensStack().lens(index)->snapshot()->region;
    const int stepsBefore = controller->undoCount();

    drag(*controller, {80.f, 60.f}, {100.f, 70.f});

    const LensRegion after = controller->lensStack().lens(index)->snapshot()->region;
    expectVec2Eq(after.center(), before.center() + glm::vec2(20.f / kWidth, 10.f / kHeight));
    expectVec2Eq(after.size(), before.size());
    EXPECT_EQ(controller->undoCount(), stepsBefore + 1) << "one drag, one step";
    EXPECT_EQ(controller->selectedLens(), index);
    EXPECT_FALSE(controller->isDragging());

    controller->undo();
    EXPECT_EQ(controller->lensStack().lens(index)->snapshot()->region, before);
    controller->redo();
    EXPECT_EQ(controller->lensStack().lens(index)->snapshot()->region, after);
}

TEST_F(ControllerLensEditTest, DraggingAPolygonMovesEveryPointByTheDelta) {
    auto controller = makeController();
    const int index = controller->addLens("achromatic", {0.5f, 0.5f});
    const std::vector<glm::vec2> points{{0.3f, 0.3f}, {0.7f, 0.35f}, {0.5f, 0.8f}};
    controller->setLensRegion(index, LensRegion::polygon(points));
    drag(*controller, pixelOf({0.5f, 0.45f}), pixelOf({0.5f, 0.45f}) + glm::vec2(-16.f, 12.f));
    const LensRegion moved = controller->lensStack().lens(index)->snapshot()->region;
    ASSERT_EQ(moved.points().size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        expectVec2Eq(moved.points()[i], points[i] + glm::vec2(-16.f / kWidth, 12.f / kHeight));
}

TEST_F(ControllerLensEditTest, CornerHandleResizesAndTheOppositeCornerStays) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.5f, 0.5f});
    controller->setLensRegion(index, LensRegion::ellipse({0.5f, 0.5f}, {0.5f, 0.5f}));
    ASSERT_EQ(controller->selectedLens(), index);
    // Bottom-right corner of the bounding box: (0.75, 0.75).
    const LensHit hit = controller->hitTest(pixelOf({0.75f, 0.75f}));
    ASSERT_EQ(hit.target, LensHit::Target::Handle);
    EXPECT_EQ(hit.handle.kind, LensHandle::Kind::Corner);
    EXPECT_EQ(hit.handle.index, 2);

    drag(*controller, pixelOf({0.75f, 0.75f}), pixelOf({0.75f, 0.75f}) + glm::vec2(16.f, 12.f));
    const LensRegion region = controller->lensStack().lens(index)->snapshot()->region;
    EXPECT_EQ(region.shape(), LensRegion::Shape::Ellipse);
    const glm::vec2 topLeft = region.center() - 0.5f * region.size();
    const glm::vec2 bottomRight = region.center() + 0.5f * region.size();
    expectVec2Eq(topLeft, {0.25f, 0.25f});
    expectVec2Eq(bottomRight, glm::vec2(0.75f) + glm::vec2(16.f / kWidth, 12.f / kHeight));
}

TEST_F(ControllerLensEditTest, EdgeHandleMovesOneSideAndNeverTurnsTheRegionInsideOut) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.5f, 0.5f});
    controller->setLensRegion(index, LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f})); // 0.25..0.75
    // Left edge midpoint, dragged far past the right edge.
    drag(*controller, pixelOf({0.25f, 0.5f}), pixelOf({0.95f, 0.5f}));
    const LensRegion region = controller->lensStack().lens(index)->snapshot()->region;
    EXPECT_FLOAT_EQ(region.center().x + 0.5f * region.size().x, 0.75f) << "the right side stays";
    EXPECT_GT(region.size().x, 0.f);
    EXPECT_FLOAT_EQ(region.size().y, 0.5f) << "an edge moves one axis only";
    EXPECT_NO_THROW(region.validate());
}

TEST_F(ControllerLensEditTest, PolygonVertexIsAHandleThatMovesAlone) {
    auto controller = makeController();
    const int index = controller->addLens("shadow", {0.5f, 0.5f});
    const std::vector<glm::vec2> points{{0.2f, 0.2f}, {0.8f, 0.25f}, {0.6f, 0.8f}, {0.25f, 0.7f}};
    controller->setLensRegion(index, LensRegion::polygon(points));
    EXPECT_EQ(controller->lensHandles(index).size(), points.size());
    drag(*controller, pixelOf(points[2]), pixelOf(points[2]) + glm::vec2(8.f, -4.f));
    const LensRegion region = controller->lensStack().lens(index)->snapshot()->region;
    ASSERT_EQ(region.points().size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::vec2 expected = i == 2 ? points[i] + glm::vec2(8.f / kWidth, -4.f / kHeight) : points[i];
        expectVec2Eq(region.points()[i], expected);
    }
}

TEST_F(ControllerLensEditTest, PickingTakesTheTopmostEnabledLens) {
    auto controller = makeController();
    const int bottom = controller->addLens("layer", {0.5f, 0.5f});
    const int top = controller->addLens("achromatic", {0.6f, 0.5f});
    const glm::vec2 overlap = pixelOf({0.55f, 0.5f});
    EXPECT_EQ(controller->lensAt(overlap), top);
    controller->setLensEnabled(top, false);
    EXPECT_EQ(controller->lensAt(overlap), bottom) << "a disabled lens is not picked";
    EXPECT_EQ(controller->lensAt(pixelOf({0.05f, 0.05f})), -1);
}

TEST_F(ControllerLensEditTest, PickingIncludesTheOutline) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.5f, 0.5f});
    LensRegion region = LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f});
    region.setOutlineWidth(6.f);
    controller->setLensRegion(index, region);
    // Two pixels outside the left side (x = 40): on the outer half of the outline.
    EXPECT_EQ(controller->lensAt({38.f, 60.f}), index);
    EXPECT_EQ(controller->lensAt({34.f, 60.f}), -1);
}

TEST_F(ControllerLensEditTest, PageUpAndPageDownReorderAndTheSelectionFollows) {
    auto controller = makeController();
    controller->addLens("layer", {0.3f, 0.5f});
    controller->addLens("achromatic", {0.5f, 0.5f});
    controller->addLens("shadow", {0.7f, 0.5f});
    controller->setSelectedLens(0);
    press(*controller, Key::PageUp);
    EXPECT_EQ(controller->lensStack().lens(1)->typeName(), "layer");
    EXPECT_EQ(controller->selectedLens(), 1);
    press(*controller, Key::PageUp);
    press(*controller, Key::PageUp); // already on top: nothing
    EXPECT_EQ(controller->lensStack().lens(2)->typeName(), "layer");
    EXPECT_EQ(controller->selectedLens(), 2);
    press(*controller, Key::PageDown);
    EXPECT_EQ(controller->lensStack().lens(1)->typeName(), "layer");
    controller->moveLens(0, 2);
    EXPECT_EQ(controller->lensStack().lens(2)->typeName(), "achromatic");
    EXPECT_EQ(controller->selectedLens(), 0) << "the selected lens moved down by one";
    EXPECT_EQ(controller->lensStack().lens(0)->typeName(), "layer");
}

TEST_F(ControllerLensEditTest, KeyEEnablesAndDisablesTheSelectedLens) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.5f, 0.5f});
    press(*controller, Key::E);
    EXPECT_FALSE(controller->lensStack().lens(index)->snapshot()->enabled);
    press(*controller, Key::E);
    EXPECT_TRUE(controller->lensStack().lens(index)->snapshot()->enabled);
    controller->undo();
    EXPECT_FALSE(controller->lensStack().lens(index)->snapshot()->enabled);
}

TEST_F(ControllerLensEditTest, DuplicateCopiesEverythingButThePlaceAndDeleteRemoves) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.4f, 0.4f});
    controller->setLensProperty(index, "layers", "2-");
    controller->setLensLabel(index, "reveal");
    press(*controller, Key::D, KeyModifier::Control);
    ASSERT_EQ(controller->lensCount(), 2);
    EXPECT_EQ(controller->selectedLens(), 1);
    LensState original = controller->state().lenses[0];
    const LensState copy = controller->state().lenses[1];
    expectVec2Eq(copy.region.center(), original.region.center() + glm::vec2(Controller::kDuplicateOffset));
    original.region = copy.region;
    EXPECT_EQ(copy, original);

    press(*controller, Key::Delete);
    EXPECT_EQ(controller->lensCount(), 1);
    EXPECT_EQ(controller->selectedLens(), -1);
    controller->undo();
    EXPECT_EQ(controller->lensCount(), 2);
}

TEST_F(ControllerLensEditTest, EveryRegisteredTypeCanBeAddedAtAPosition) {
    auto controller = makeController();
    const std::vector<std::string> types = registry->lensTypes();
    ASSERT_GE(types.size(), 4u);
    for (const std::string &type : types) {
        const int index = controller->addLens(type, {0.3f, 0.6f});
        EXPECT_EQ(controller->lensStack().lens(index)->typeName(), type);
        expectVec2Eq(controller->lensStack().lens(index)->snapshot()->region.center(), {0.3f, 0.6f});
        EXPECT_TRUE(controller->lensStack().lens(index)->snapshot()->enabled);
        EXPECT_EQ(controller->selectedLens(), index);
    }
    EXPECT_EQ(controller->undoCount(), int(types.size()));
    const std::string unknown = errorOf([&] { controller->addLens("nosuchlens", {0.5f, 0.5f}); });
    EXPECT_NE(unknown.find("nosuchlens"), std::string::npos) << unknown;
    EXPECT_EQ(controller->lensCount(), int(types.size()));
}

TEST_F(ControllerLensEditTest, PropertyEditsUseTheTextFormAndErrorsNameLensAndProperty) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.5f, 0.5f});
    controller->setLensLabel(index, "reveal");
    controller->setLensProperty(index, "distance", "2.5");
    EXPECT_EQ(controller->lensProperty(index, "distance"), "2.5");
    const SessionState before = controller->state();
    const int steps = controller->undoCount();

    const std::string bad = errorOf([&] { controller->setLensProperty(index, "distance", "-1"); });
    EXPECT_NE(bad.find("lens 0 'reveal' (layer)"), std::string::npos) << bad;
    EXPECT_NE(bad.find("distance"), std::string::npos) << bad;
    const std::string unknown = errorOf([&] { controller->setLensProperty(index, "strenght", "1"); });
    EXPECT_NE(unknown.find("strenght"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("'reveal'"), std::string::npos) << unknown;
    EXPECT_EQ(controller->state(), before);
    EXPECT_EQ(controller->undoCount(), steps);
    EXPECT_FALSE(controller->lensStack().lens(index)->hasUncommittedChanges()) << "nothing bad left staged";
}

TEST_F(ControllerLensEditTest, EditsReachTheRenderSession) {
    auto controller = makeController();
    RenderSession &session = controller->renderSession();
    session.renderUntilIdle();
    const int index = controller->addLens("achromatic", {0.5f, 0.5f});
    EXPECT_EQ(session.renderPass().kind, PassKind::Retrace);
    drag(*controller, pixelOf({0.5f, 0.5f}), pixelOf({0.5f, 0.5f}) + glm::vec2(10.f, 0.f));
    const RenderPassStats moved = session.renderPass();
    EXPECT_EQ(moved.kind, PassKind::Retrace);
    EXPECT_GT(moved.pixelsRestarted, 0u);
    session.renderUntilIdle();
    controller->setLensEnabled(index, false);
    EXPECT_EQ(session.renderPass().kind, PassKind::Retrace);
    controller->setLayerVisibility(0, LayerVisibility::Hidden);
    EXPECT_EQ(session.renderPass().kind, PassKind::Retrace);
    controller->orbit(0.3f, 0.f);
    EXPECT_EQ(session.camera(), controller->camera());
}

TEST_F(ControllerLensEditTest, EscapeCancelsADragWithoutAStep) {
    auto controller = makeController();
    const int index = controller->addLens("layer", {0.5f, 0.5f});
    const SessionState before = controller->state();
    const int steps = controller->undoCount();
    controller->handle(InputEvent::pointerPress({80.f, 60.f}, PointerButton::Left));
    controller->handle(InputEvent::pointerMove({120.f, 90.f}));
    EXPECT_TRUE(controller->isDragging());
    EXPECT_EQ(controller->dragKind(), DragKind::MoveLens);
    press(*controller, Key::Escape);
    EXPECT_FALSE(controller->isDragging());
    controller->handle(InputEvent::pointerRelease({120.f, 90.f}, PointerButton::Left));
    EXPECT_EQ(controller->state(), before);
    EXPECT_EQ(controller->undoCount(), steps);
    EXPECT_EQ(controller->selectedLens(), index);
}

TEST_F(ControllerLensEditTest, ClickOnTheEmptyImageDeselects) {
    auto controller = makeController();
    controller->addLens("layer", {0.5f, 0.5f});
    ASSERT_EQ(controller->selectedLens(), 0);
    controller->handle(InputEvent::pointerPress({5.f, 5.f}, PointerButton::Left));
    controller->handle(InputEvent::pointerRelease({5.f, 5.f}, PointerButton::Left));
    EXPECT_EQ(controller->selectedLens(), -1);
}

} // namespace
} // namespace mvcl::test
