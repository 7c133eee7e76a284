// Document: several views of one scene — routing, focus, one history across views, links
// (camera, lenses, layers) also after a model reload and a session round trip, and no state
// leaking between views that are not linked.

#include "controller/ControllerFixture.h"

#include <mvcl/controller/Document.h>
#include <mvcl/io/SessionFile.h>

#include <fstream>
#include <sstream>

namespace mvcl::test {
namespace {

class DocumentTest : public ControllerFixture {
protected:
    static std::unique_ptr<Document> makeDocument(int views = 2, const RenderSettings &settings = smallSettings()) {
        auto document = std::make_unique<Document>(*registry, cubeRequest(), settings);
        while (document->viewCount() < views) document->addView();
        // Side by side, as the viewer lays out "1x2": view i at x = i · kWidth.
        std::vector<ViewRect> rects;
        for (int i = 0; i < document->viewCount(); ++i) rects.push_back({i, {i * kWidth, 0}, {kWidth, kHeight}});
        document->setViewRects(rects);
        return document;
    }
    /// Window position of a normalised position in view `view` (views side by side).
    static glm::vec2 windowPixel(int view, const glm::vec2 &normalized) {
        return pixelOf(normalized) + glm::vec2(float(view * kWidth), 0.f);
    }
    static void dragIn(Document &document, const glm::vec2 &from, const glm::vec2 &to, int steps = 4) {
        document.handle(InputEvent::pointerPress(from, PointerButton::Left));
        for (int i = 1; i <= steps; ++i)
            document.handle(InputEvent::pointerMove(from + (to - from) * (float(i) / float(steps))));
        document.handle(InputEvent::pointerRelease(to, PointerButton::Left));
    }
    static std::string readText(const std::filesystem::path &file) {
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }
};

TEST_F(DocumentTest, ViewsShareOneSceneAndTracer) {
    auto document = makeDocument(3);
    ASSERT_EQ(document->viewCount(), 3);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(&document->view(i).tracer(), &document->tracer());
        EXPECT_EQ(&document->view(i).scene(), &document->scene());
    }
    EXPECT_NE(&document->view(0).renderSession(), &document->view(1).renderSession());
    // A new view shows what the focused one shows.
    EXPECT_EQ(document->view(2).state(), document->view(0).state());
    EXPECT_THROW(document->view(3), Error);
    document->addView();
    EXPECT_THROW(document->addView(), Error); // four at most
}

TEST_F(DocumentTest, PointerEventsGoToTheViewUnderThePointerAndAPressFocusesIt) {
    auto document = makeDocument(2);
    const Camera before0 = document->view(0).camera(), before1 = document->view(1).camera();
    dragIn(*document, windowPixel(1, {0.1f, 0.1f}), windowPixel(1, {0.4f, 0.3f})); // orbit in view 1
    EXPECT_EQ(document->focusedView(), 1);
    EXPECT_EQ(document->view(0).camera(), before0);
    EXPECT_NE(document->view(1).camera(), before1);

    // The pressed view keeps the pointer until release, even when it leaves the view.
    const Camera moved1 = document->view(1).camera();
    dragIn(*document, windowPixel(1, {0.1f, 0.1f}), windowPixel(0, {0.2f, 0.8f}));
    EXPECT_EQ(document->view(0).camera(), before0);
    EXPECT_NE(document->view(1).camera(), moved1);

    // Keys go to the focused view.
    document->setFocusedView(0);
    const Camera dragged1 = document->view(1).camera();
    document->handle(InputEvent::keyPress(Key::Digit5)); // top view
    EXPECT_NE(document->view(0).camera(), before0);
    EXPECT_EQ(document->view(1).camera(), dragged1);

    // A lens added in one view is only there.
    document->view(0).addLens("layer", {0.5f, 0.5f});
    EXPECT_EQ(document->view(0).lensCount(), 1);
    EXPECT_EQ(document->view(1).lensCount(), 0);
}

TEST_F(DocumentTest, OneHistoryAcrossViewsAndUndoFocusesTheViewOfTheStep) {
    auto document = makeDocument(2);
    std::vector<DocumentState> states{document->state()};
    document->view(0).addLens("layer", {0.3f, 0.5f});
    states.push_back(document->state());
    document->view(1).addLens("shadow", {0.6f, 0.5f});
    states.push_back(document->state());
    dragIn(*document, windowPixel(0, {0.9f, 0.1f}), windowPixel(0, {0.7f, 0.3f})); // orbit view 0
    states.push_back(document->state());
    document->view(1).setLayerVisibility(1, LayerVisibility::Hidden);
    states.push_back(document->state());

    ASSERT_EQ(document->undoCount(), 4);
    EXPECT_EQ(document->view(0).undoCount(), 4); // a view's history is the document's
    const int stepViews[] = {0, 1, 0, 1};
    for (int i = 3; i >= 0; --i) {
        EXPECT_EQ(document->undoView(), stepViews[i]);
        document->setFocusedView(1 - stepViews[i]);
        document->undo();
        EXPECT_EQ(document->state(), states[std::size_t(i)]) << "after undoing step " << i + 1;
        EXPECT_EQ(document->focusedView(), stepViews[i]);
    }
    for (int i = 1; i <= 4; ++i) {
        document->view(i % 2).redo(); // through any view
        EXPECT_EQ(document->state(), states[std::size_t(i)]) << "after redoing step " << i;
    }
    // Ctrl+Z in whichever view is focused undoes the last step of any view.
    document->setFocusedView(0);
    document->handle(InputEvent::keyPress(Key::Z, KeyModifier::Control));
    EXPECT_EQ(document->state(), states[3]);
}

TEST_F(DocumentTest, LinkedCamerasFollowEachOtherBothWaysAndAnOrbitIsOneStep) {
    auto document = makeDocument(2);
    document->view(1).orbit(0.5f, 0.2f);
    ASSERT_NE(document->view(0).camera(), document->view(1).camera());
    document->setFocusedView(1);
    document->link(0, 1, LinkAspect::Camera); // copies from the focused view
    EXPECT_EQ(document->view(0).camera(), document->view(1).camera());
    EXPECT_TRUE(document->isLinked(1, 0, LinkAspect::Camera));
    EXPECT_FALSE(document->isLinked(0, 1, LinkAspect::Lenses));

    const int steps = document->undoCount();
    dragIn(*document, windowPixel(0, {0.2f, 0.2f}), windowPixel(0, {0.5f, 0.4f}));
    EXPECT_EQ(document->view(0).camera(), document->view(1).camera());
    EXPECT_EQ(document->view(1).renderSession().camera(), document->view(0).camera()); // sent to its session
    EXPECT_EQ(document->undoCount(), steps + 1);
    dragIn(*document, windowPixel(1, {0.5f, 0.5f}), windowPixel(1, {0.3f, 0.5f})); // the other way
    EXPECT_EQ(document->view(0).camera(), document->view(1).camera());
    document->view(0).zoomAt(pixelOf({0.5f, 0.5f}), 0.8f);
    EXPECT_EQ(document->view(0).camera(), document->view(1).camera());

    // Lenses and layers are not linked.
    document->view(0).addLens("layer", {0.5f, 0.5f});
    document->view(0).setLayerVisibility(2, LayerVisibility::Hidden);
    EXPECT_EQ(document->view(1).lensCount(), 0);
    EXPECT_EQ(document->view(1).visibleLayers(), kAllLayers);

    document->unlink(0, 1, LinkAspect::Camera);
    EXPECT_TRUE(document->links().empty());
    const Camera alone = document->view(1).camera();
    document->view(0).orbit(0.3f, 0.f);
    EXPECT_EQ(document->view(1).camera(), alone);
    document->undo(); // the orbit
    document->undo(); // the unlink
    EXPECT_TRUE(document->isLinked(0, 1, LinkAspect::Camera));
}

TEST_F(DocumentTest, LinkedLensStacksShowEveryEditInBothViewsWithTheirOwnLensObjects) {
    auto document = makeDocument(2);
    document->view(0).addLens("layer", {0.4f, 0.5f});
    document->setFocusedView(0);
    document->link(0, 1, LinkAspect::Lenses);
    ASSERT_EQ(document->view(1).lensCount(), 1);
    EXPECT_NE(document->view(0).lensStack().lens(0), document->view(1).lensStack().lens(0));

    document->view(1).setLensProperty(0, "layers", "2-");
    EXPECT_EQ(document->view(0).lensProperty(0, "layers"), document->view(1).lensProperty(0, "layers"));
    // A lens dragged in one view moves in the other during the drag.
    const glm::vec2 start = windowPixel(0, {0.4f, 0.5f});
    document->handle(InputEvent::pointerPress(start, PointerButton::Left));
    document->handle(InputEvent::pointerMove(start + glm::vec2(16.f, 0.f)));
    EXPECT_EQ(document->view(1).lensStack().lens(0)->snapshot()->region,
              document->view(0).lensStack().lens(0)->snapshot()->region);
    document->handle(InputEvent::pointerRelease(start + glm::vec2(16.f, 0.f), PointerButton::Left));
    document->view(1).addLens("shadow", {0.7f, 0.3f});
    document->view(0).removeLens(0);
    EXPECT_EQ(document->view(0).state().lenses, document->view(1).state().lenses);
    EXPECT_EQ(document->view(1).lensCount(), 1);
    // Cameras stay apart.
    document->view(0).orbit(0.4f, 0.f);
    EXPECT_NE(document->view(0).camera(), document->view(1).camera());
}

TEST_F(DocumentTest, LinkedLayersAndChainsOfLinks) {
    auto document = makeDocument(3);
    document->setFocusedView(0);
    document->link(0, 1, LinkAspect::Layers);
    document->link(1, 2, LinkAspect::Layers);
    document->view(2).setLayerVisibility(1, LayerVisibility::Hidden);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(document->view(i).layerVisibility(1), LayerVisibility::Hidden) << i;
    EXPECT_EQ(document->view(0).basePolicy().query(RayType::Primary).layerMask, document->view(2).visibleLayers());
    document->undo();
    for (int i = 0; i < 3; ++i) EXPECT_EQ(document->view(i).layerVisibility(1), LayerVisibility::Visible) << i;
}

TEST_F(DocumentTest, LinksSurviveASessionRoundTripAndAModelReload) {
    const std::filesystem::path folder = scratchFolder();
    auto document = makeDocument(2);
    document->setFocusedView(0);
    document->view(0).addLens("layer", {0.4f, 0.5f});
    document->link(0, 1, LinkAspect::Camera);
    document->link(0, 1, LinkAspect::Lenses);
    document->view(1).setLayerVisibility(3, LayerVisibility::Hidden);
    document->setLayout(ViewLayout::Columns);
    document->saveSession(folder / "two.json");
    EXPECT_NE(readText(folder / "two.json").find("\"version\": 2"), std::string::npos);

    ViewRequest request;
    request.sessionFile = folder / "two.json";
    auto reopened = std::make_unique<Document>(*registry, request, smallSettings());
    ASSERT_EQ(reopened->viewCount(), 2);
    EXPECT_EQ(reopened->layout(), ViewLayout::Columns);
    EXPECT_EQ(reopened->links(), document->links());
    EXPECT_EQ(reopened->state(), document->state());
    reopened->view(1).orbit(0.2f, 0.1f);
    EXPECT_EQ(reopened->view(0).camera(), reopened->view(1).camera());
    reopened->view(1).setLensProperty(0, "layers", "1");
    EXPECT_EQ(reopened->view(0).lensProperty(0, "layers"), "1");
    EXPECT_EQ(reopened->view(0).visibleLayers(), kAllLayers); // layers not linked

    // Loading into an existing document of another shape.
    auto loaded = makeDocument(1);
    loaded->loadSession(folder / "two.json");
    EXPECT_EQ(loaded->state(), document->state());

    // Reloading the model keeps the links working, both ways.
    reopened->openScenes({"builtin:cube-in-cube"});
    reopened->finishSceneLoad();
    EXPECT_EQ(reopened->links(), document->links());
    reopened->view(0).orbit(-0.3f, 0.f);
    EXPECT_EQ(reopened->view(0).camera(), reopened->view(1).camera());
    reopened->view(1).addLens("shadow", {0.5f, 0.5f});
    EXPECT_EQ(reopened->view(0).lensCount(), 2);
    EXPECT_EQ(reopened->view(0).state().lenses, reopened->view(1).state().lenses);
}

TEST_F(DocumentTest, ALayersLinkHoldsBothWaysAfterASessionRoundTripAndAModelReload) {
    const std::filesystem::path folder = scratchFolder();
    auto document = makeDocument(2);
    document->setFocusedView(1);
    document->view(1).setLayerVisibility(2, LayerVisibility::Hidden);
    document->link(0, 1, LinkAspect::Layers); // from the focused view 1
    EXPECT_EQ(document->view(0).layerVisibility(2), LayerVisibility::Hidden);
    document->saveSession(folder / "layers.json");

    auto reopened = makeDocument(1);
    reopened->loadSession(folder / "layers.json");
    ASSERT_EQ(reopened->viewCount(), 2);
    EXPECT_EQ(reopened->focusedView(), 1);
    reopened->view(0).setLayerVisibility(0, LayerVisibility::Hidden);
    EXPECT_EQ(reopened->view(1).visibleLayers(), reopened->view(0).visibleLayers());
    reopened->openScenes({"builtin:cube-in-cube"}); // every layer visible again, then the link
    reopened->finishSceneLoad();
    EXPECT_EQ(reopened->view(0).visibleLayers(), kAllLayers);
    reopened->view(1).setLayerVisibility(1, LayerVisibility::Hidden);
    EXPECT_EQ(reopened->view(0).layerVisibility(1), LayerVisibility::Hidden);
    reopened->view(0).setLayerVisibility(1, LayerVisibility::Visible);
    EXPECT_EQ(reopened->view(1).layerVisibility(1), LayerVisibility::Visible);
    // A session loaded into the document replaces its links too.
    reopened->unlink(0, 1, LinkAspect::Layers);
    reopened->loadSession(folder / "layers.json");
    EXPECT_TRUE(reopened->isLinked(0, 1, LinkAspect::Layers));
    EXPECT_FALSE(reopened->canUndo());
}

TEST_F(DocumentTest, ASessionWhoseLayoutHasMoreCellsThanViewsGetsItsViewsFilledIn) {
    const std::filesystem::path file = scratchFolder() / "grid.json";
    std::ofstream(file) << R"({"version": 2, "scene": "builtin:cube-in-cube", "layout": "2x2", "focus": 1,
        "views": [{"visibleLayers": "1-"}, {"lenses": [{"type": "layer"}]}]})";
    ViewRequest request;
    request.sessionFile = file;
    const Document document(*registry, request, smallSettings());
    ASSERT_EQ(document.viewCount(), 4);
    EXPECT_EQ(document.shownViews(), (std::vector<int>{0, 1, 2, 3}));
    // The added views are copies of the focused view 1.
    EXPECT_EQ(document.view(2).state(), document.view(1).state());
    EXPECT_EQ(document.view(0).visibleLayers(), ~uint32_t(1));
}

TEST_F(DocumentTest, AOneViewSessionIsWrittenAsVersionOneByteForByte) {
    const std::filesystem::path folder = scratchFolder();
    auto controller = makeController();
    controller->addLens("layer", {0.4f, 0.5f});
    controller->setLayerVisibility(2, LayerVisibility::Hidden);
    controller->saveSession(folder / "one-controller.json");

    ViewRequest request;
    request.sessionFile = folder / "one-controller.json";
    auto document = std::make_unique<Document>(*registry, request, smallSettings());
    ASSERT_EQ(document->viewCount(), 1);
    document->saveSession(folder / "one-document.json");
    EXPECT_EQ(readText(folder / "one-document.json"), readText(folder / "one-controller.json"));
}

TEST_F(DocumentTest, UnlinkedViewsKeepTheirOwnState) {
    auto document = makeDocument(4);
    document->view(2).addLens("layer", {0.5f, 0.5f});
    document->view(2).setSelectedLens(0);
    document->view(2).setLayerVisibility(1, LayerVisibility::Hidden);
    document->view(2).setCompareEnabled(true);
    dragIn(*document, windowPixel(3, {0.2f, 0.2f}), windowPixel(3, {0.6f, 0.4f}));
    for (int i : {0, 1}) {
        EXPECT_EQ(document->view(i).lensCount(), 0) << i;
        EXPECT_EQ(document->view(i).selectedLens(), -1) << i;
        EXPECT_EQ(document->view(i).visibleLayers(), kAllLayers) << i;
        EXPECT_FALSE(document->view(i).isCompareEnabled()) << i;
        EXPECT_EQ(document->view(i).camera(), document->view(0).camera());
    }
    EXPECT_NE(document->view(3).camera(), document->view(0).camera());
    EXPECT_EQ(document->view(3).lensCount(), 0);
    EXPECT_EQ(document->view(2).camera(), document->view(0).camera());
}

TEST_F(DocumentTest, CompareDividerDragIsOneStepAndPressesPickTheSide) {
    auto document = makeDocument(1);
    document->view(0).addLens("layer", {0.25f, 0.5f});
    document->view(0).setCompareEnabled(true);
    Controller &view = document->view(0);
    ASSERT_TRUE(view.isCompareEnabled());
    EXPECT_EQ(view.rightLensStack().size(), 1);
    EXPECT_NE(view.rightLensStack().lens(0), view.leftLensStack().lens(0));
    const int steps = document->undoCount();

    dragIn(*document, pixelOf({0.5f, 0.5f}), pixelOf({0.75f, 0.5f}));
    EXPECT_NEAR(view.compareDivider(), 0.75f, 1e-6f);
    EXPECT_EQ(document->undoCount(), steps + 1);
    EXPECT_EQ(view.state().compare->divider, view.compareDivider());

    // A press right of the divider edits the right stack; the left keeps its lens.
    document->handle(InputEvent::pointerPress(pixelOf({0.9f, 0.5f}), PointerButton::Left));
    document->handle(InputEvent::pointerRelease(pixelOf({0.9f, 0.5f}), PointerButton::Left));
    EXPECT_EQ(view.compareSide(), CompareSide::Right);
    view.removeLens(0);
    EXPECT_EQ(view.state().lenses.size(), 1u);
    EXPECT_TRUE(view.state().compare->lenses.empty());

    // The divider and both stacks are part of the session.
    const std::filesystem::path file = scratchFolder() / "compare.json";
    document->saveSession(file);
    ViewRequest request;
    request.sessionFile = file;
    const Document reopened(*registry, request, smallSettings());
    EXPECT_EQ(reopened.state(), document->state());
    EXPECT_TRUE(reopened.view(0).isCompareEnabled());

    document->undo(); // the removal
    EXPECT_EQ(view.state().compare->lenses.size(), 1u);
    document->undo(); // the divider
    EXPECT_NEAR(view.compareDivider(), 0.5f, 1e-6f);
    view.setCompareEnabled(false);
    EXPECT_FALSE(view.state().compare.has_value());
    EXPECT_EQ(view.lensCount(), 1);
}

TEST_F(DocumentTest, TheFocusedViewRefinesFirstAndLinkedCamerasShareThePreviewBudget) {
    RenderSettings settings = smallSettings();
    settings.previewBudgetSeconds = 0.04;
    auto document = makeDocument(2, settings);
    document->setFocusedView(0);
    document->updateRenderPriority(); // view 0 has everything to render
    EXPECT_FALSE(document->view(0).renderSession().isRefinementHeld());
    EXPECT_TRUE(document->view(1).renderSession().isRefinementHeld());
    document->view(0).renderSession().renderUntilIdle();
    document->updateRenderPriority();
    EXPECT_FALSE(document->view(1).renderSession().isRefinementHeld());

    const double budget = settings.previewBudgetSeconds;
    document->link(0, 1, LinkAspect::Camera);
    EXPECT_EQ(document->view(0).renderSettings().previewBudgetSeconds, budget / 2);
    EXPECT_EQ(document->view(1).renderSettings().previewBudgetSeconds, budget / 2);
    document->link(0, 1, LinkAspect::Lenses); // not a camera link: no change
    document->unlink(0, 1, LinkAspect::Camera);
    EXPECT_EQ(document->view(1).renderSettings().previewBudgetSeconds, budget);
    document->undo(); // the camera link again
    EXPECT_EQ(document->view(1).renderSettings().previewBudgetSeconds, budget / 2);
}

} // namespace
} // namespace mvcl::test
