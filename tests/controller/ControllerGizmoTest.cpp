// The 3D handles through the Controller: offered from the declarations of the real clip and
// section plugins, hovered, dragged as one undo step with priority over Shift-pan, fitted, a
// lens pinned to the pointer, and sessions that keep oriented boxes, spared layers and the old
// clip box form.

#include "ControllerFixture.h"

#include <mvcl/lens/PropertyValue.h>

#include <glm/geometric.hpp>

#include <fstream>

namespace mvcl::test {
namespace {

class ControllerGizmoTest : public ControllerFixture {
protected:
    static void SetUpTestSuite() {
        ControllerFixture::SetUpTestSuite();
        for (const char *name : {"clip", "section", "peel", "xray"})
            registry->loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / (std::string("mvcl-lens-") + name + ".so"));
    }

    static GizmoHandle handleNamed(const Controller &controller, int lens, const std::string &name) {
        for (const GizmoHandle &handle : controller.gizmoHandles(lens))
            if (handle.name() == name) return handle;
        ADD_FAILURE() << "no handle " << name;
        return {};
    }

    static Box3d boxOf(const Controller &controller, int lens) {
        return findProperty(controller.lensStack().lens(lens)->properties(), "box")
            ->parse(controller.lensProperty(lens, "box"))
            .toBox3();
    }

    /// Screen direction of the box's x axis at the handle.
    static glm::vec2 screenX(const Controller &controller, const GizmoHandle &handle) {
        const GizmoView view = controller.gizmoView();
        return glm::normalize(*view.pixelFromScene(handle.anchor + glm::dvec3(0.01, 0.0, 0.0)) - handle.pixel);
    }
};

TEST_F(ControllerGizmoTest, TheClipLensOffersHandlesForTheVolumeInUseOnly) {
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    std::vector<GizmoShape> shapes = controller->gizmoShapes(0);
    ASSERT_EQ(shapes.size(), 1u);
    EXPECT_EQ(shapes[0].decl.kind, GizmoDecl::Kind::Box);
    EXPECT_EQ(shapes[0].decl.rotation, "boxRotation");
    controller->setLensProperty(0, "volume", "sphere");
    shapes = controller->gizmoShapes(0);
    ASSERT_EQ(shapes.size(), 1u);
    EXPECT_EQ(shapes[0].decl.kind, GizmoDecl::Kind::Sphere);
    controller->setLensProperty(0, "volume", "halfSpace");
    EXPECT_EQ(controller->gizmoShapes(0).at(0).decl.kind, GizmoDecl::Kind::Plane);
    // section: a plane once it is fixed in the model.
    controller->addLens("section", {0.5f, 0.5f});
    EXPECT_TRUE(controller->gizmoShapes(1).empty()) << "facing the view, it has nothing to grab";
    controller->setLensProperty(1, "facing", "plane");
    EXPECT_EQ(controller->gizmoShapes(1).at(0).decl.kind, GizmoDecl::Kind::Plane);
}

TEST_F(ControllerGizmoTest, TheBoxSitsWhereTheClipCuts) {
    // frame=scene: the declared bounds space is what the lens cuts, and so what the gizmo shows.
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    controller->setLensProperty(0, "box", "0.25,0.25,0.25,0.75,1,0.5");
    const GizmoShape box = controller->gizmoShapes(0).at(0);
    const ClipVolume &cut = controller->lensStack().lens(0)->snapshot()->contribution.visibility[0].clip(0);
    EXPECT_NEAR(box.center.x - box.halfExtent.x, cut.boxMin().x, 1e-5);
    EXPECT_NEAR(box.center.y + box.halfExtent.y, cut.boxMax().y, 1e-5);
    EXPECT_NEAR(box.center.z + box.halfExtent.z, cut.boxMax().z, 1e-5);
}

TEST_F(ControllerGizmoTest, AFaceDragIsOneUndoStepAndMovesOnlyThatFace) {
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    controller->setLensProperty(0, "box", "0.25,0.25,0.25,0.75,0.75,0.75");
    const Box3d before = boxOf(*controller, 0);
    const int steps = controller->undoCount();
    const GizmoHandle face = handleNamed(*controller, 0, "+x");
    const glm::vec2 along = screenX(*controller, face);
    drag(*controller, face.pixel, face.pixel + 12.f * along);
    const Box3d after = boxOf(*controller, 0);
    EXPECT_GT(after.max.x, before.max.x);
    EXPECT_NEAR(after.min.x, before.min.x, 1e-9);
    EXPECT_NEAR(after.max.y, before.max.y, 1e-9);
    EXPECT_EQ(controller->undoCount(), steps + 1);
    EXPECT_EQ(controller->dragKind(), DragKind::None);
    controller->undo();
    EXPECT_EQ(boxOf(*controller, 0), before);
}

TEST_F(ControllerGizmoTest, AHandleWinsOverShiftPanAndOrbit) {
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    controller->setLensProperty(0, "box", "0.25,0.25,0.25,0.75,0.75,0.75");
    const Camera camera = controller->camera();
    const GizmoHandle center = handleNamed(*controller, 0, "center");
    EXPECT_EQ(controller->hitTest(center.pixel).target, LensHit::Target::Gizmo);
    controller->handle(InputEvent::pointerPress(center.pixel, PointerButton::Left, KeyModifier::Shift));
    EXPECT_EQ(controller->dragKind(), DragKind::Gizmo);
    controller->handle(InputEvent::pointerMove(center.pixel + glm::vec2(0.f, -10.f), KeyModifier::Shift));
    controller->handle(InputEvent::pointerRelease(center.pixel + glm::vec2(0.f, -10.f), PointerButton::Left));
    EXPECT_EQ(controller->camera(), camera);
    EXPECT_NE(boxOf(*controller, 0).min, Box3d{}.min);
}

TEST_F(ControllerGizmoTest, TheHandleUnderThePointerIsHighlighted) {
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    controller->setLensProperty(0, "box", "0.25,0.25,0.25,0.75,0.75,0.75");
    const GizmoHandle face = handleNamed(*controller, 0, "-y");
    EXPECT_TRUE(controller->handle(InputEvent::pointerMove(face.pixel + glm::vec2(3.f, 2.f))));
    int hovered = 0;
    for (const GizmoDrawing::Dot &dot : controller->gizmoDrawing().dots) hovered += dot.state == GizmoDrawing::State::Hovered;
    EXPECT_EQ(hovered, 1);
    EXPECT_FALSE(controller->handle(InputEvent::pointerMove(face.pixel + glm::vec2(3.f, 3.f)))) << "nothing new";
    controller->setSelectedLens(-1);
    EXPECT_TRUE(controller->gizmoDrawing().dots.empty()) << "only the selected lens shows handles";
}

TEST_F(ControllerGizmoTest, ScriptedHandleDragsMatchPointerDragsAndNameWhatIsDrawn) {
    auto a = makeController(), b = makeController();
    for (Controller *c : {a.get(), b.get()}) {
        c->addLens("clip", {0.5f, 0.5f});
        c->setLensProperty(0, "box", "0.25,0.25,0.25,0.75,0.75,0.75");
    }
    const GizmoHandle ring = handleNamed(*a, 0, "rotate-z");
    drag(*a, ring.pixel, ring.pixel + glm::vec2(6.f, 9.f), PointerButton::Left, KeyModifier::None, 1);
    b->dragGizmoHandle(0, "rotate-z", {6.f, 9.f});
    EXPECT_EQ(a->lensProperty(0, "boxRotation"), b->lensProperty(0, "boxRotation"));
    EXPECT_NE(b->lensProperty(0, "boxRotation"), PropertyValue::transform(glm::dmat4(1.0)).toString());
    EXPECT_EQ(b->undoCount(), a->undoCount());
    try {
        b->dragGizmoHandle(0, "radius", {1.f, 1.f});
        FAIL() << "a box has no radius";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("radius"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("+x"), std::string::npos) << "lists the handles drawn: " << e.what();
    }
}

TEST_F(ControllerGizmoTest, FitSetsTheBoxToTheSceneALayerOrTheObjectUnderThePointer) {
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    controller->dragGizmoHandle(0, "rotate-x", {10.f, 10.f});
    controller->fitLens(0, LensFit::All);
    EXPECT_EQ(controller->lensProperty(0, "box"), PropertyValue::box3({{0, 0, 0}, {1, 1, 1}}).toString());
    EXPECT_EQ(controller->lensProperty(0, "boxRotation"), PropertyValue::transform(glm::dmat4(1.0)).toString());
    controller->fitLens(0, LensFit::Layer, 1); // the inner cube
    const Box3d inner = boxOf(*controller, 0);
    EXPECT_GT(inner.min.x, 0.01);
    EXPECT_LT(inner.max.x, 0.99);
    // The object under the centre of the view: a part of the scene that holds the point shown there.
    const glm::vec2 middle = pixelOf({0.5f, 0.5f});
    const glm::dvec3 shown = controller->lensStack().lens(0)->context().propertyPoint(
        glm::dvec3(controller->pointUnder(middle)), PropertySpace::Bounds);
    controller->fitLens(0, LensFit::Object, 0, middle);
    const Box3d object = boxOf(*controller, 0);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(object.min[axis], shown[axis] + 1e-6);
        EXPECT_GE(object.max[axis], shown[axis] - 1e-6);
        EXPECT_GE(object.min[axis], -1e-6);
        EXPECT_LE(object.max[axis], 1.0 + 1e-6);
    }
    EXPECT_NE(object, Box3d({{0, 0, 0}, {1, 1, 1}})) << "one object, not the scene";
    EXPECT_THROW(controller->fitLens(0, LensFit::Layer, 7), Error) << "an empty layer";
    EXPECT_THROW(controller->fitLens(0, LensFit::Object, 0, {1.f, 1.f}), Error) << "the background";
    controller->addLens("xray", {0.5f, 0.5f});
    EXPECT_THROW(controller->fitLens(1, LensFit::All), Error) << "no box or sphere";
}

TEST_F(ControllerGizmoTest, APinnedLensFollowsThePointerWithoutUndoSteps) {
    auto controller = makeController();
    controller->addLens("xray", {0.5f, 0.5f});
    controller->setPointerFollowingLens(0);
    const int steps = controller->undoCount();
    controller->handle(InputEvent::pointerMove(pixelOf({0.3f, 0.7f})));
    glm::vec2 center = controller->lensStack().lens(0)->snapshot()->region.center();
    EXPECT_NEAR(center.x, 0.3f, 1e-5f);
    EXPECT_NEAR(center.y, 0.7f, 1e-5f);
    EXPECT_EQ(controller->undoCount(), steps);
    // P toggles it on the selected lens; the pin follows the lens when the stack reorders.
    press(*controller, Key::P);
    EXPECT_EQ(controller->pointerFollowingLens(), -1);
    press(*controller, Key::P);
    controller->addLens("peel", {0.5f, 0.5f});
    controller->moveLens(1, 0);
    EXPECT_EQ(controller->pointerFollowingLens(), 1);
    controller->handle(InputEvent::pointerMove(pixelOf({0.6f, 0.2f})));
    center = controller->lensStack().lens(1)->snapshot()->region.center();
    EXPECT_NEAR(center.x, 0.6f, 1e-5f);
}

TEST_F(ControllerGizmoTest, SessionsKeepOrientedBoxesAndSparedLayers) {
    const std::filesystem::path folder = scratchFolder();
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    controller->dragGizmoHandle(0, "rotate-y", {12.f, -7.f});
    controller->setLensProperty(0, "layers", "1");
    controller->addLens("section", {0.4f, 0.5f});
    controller->setLensProperty(1, "facing", "plane");
    controller->dragGizmoHandle(1, "normal", {-9.f, 4.f});
    controller->setLensProperty(1, "layers", "0");
    controller->saveSession(folder / "session.json");
    auto reopened = makeController();
    reopened->loadSession(folder / "session.json");
    ASSERT_EQ(reopened->lensCount(), 2);
    for (int lens = 0; lens < 2; ++lens)
        for (const PropertyDecl &decl : controller->lensStack().lens(lens)->properties())
            EXPECT_EQ(reopened->lensProperty(lens, decl.name), controller->lensProperty(lens, decl.name)) << decl.name;
    EXPECT_NE(reopened->lensProperty(0, "boxRotation"), PropertyValue::transform(glm::dmat4(1.0)).toString());
}

TEST_F(ControllerGizmoTest, AnOldSessionsClipBoxKeepsItsMeaning) {
    // Written before the declarations said which space the box is in: frame=scene (the
    // default) reads it as fractions of the scene bounds, as it always did.
    const std::filesystem::path folder = scratchFolder();
    std::ofstream(folder / "old.json") << R"({"version": 1, "scene": "builtin:cube-in-cube", "lenses": [
        {"type": "clip", "properties": {"volume": "box", "box": "0.5,0.5,0.5,1.5,1.5,1.5", "caps": "solid"}},
        {"type": "clip", "properties": {"frame": "world", "volume": "sphere", "sphereCenter": "0.1,0.2,0.3",
                                        "sphereRadius": 0.4}}]})";
    auto controller = makeController();
    controller->loadSession(folder / "old.json");
    const Bounds3f bounds = controller->scene().bounds();
    const glm::vec3 lower = bounds.min, extent = bounds.extent();
    const ClipVolume &box = controller->lensStack().lens(0)->snapshot()->contribution.visibility[0].clip(0);
    EXPECT_FALSE(box.isOriented());
    EXPECT_EQ(box.layerMask(), kAllLayers);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_FLOAT_EQ(box.boxMin()[axis], lower[axis] + 0.5f * extent[axis]);
        EXPECT_FLOAT_EQ(box.boxMax()[axis], lower[axis] + 1.5f * extent[axis]);
    }
    const ClipVolume &sphere = controller->lensStack().lens(1)->snapshot()->contribution.visibility[0].clip(0);
    const glm::vec3 center = glm::vec3(glm::dvec3(0.1, 0.2, 0.3) - controller->scene().worldOrigin);
    EXPECT_FLOAT_EQ(sphere.center().x, center.x);
    EXPECT_FLOAT_EQ(sphere.radius(), 0.4f);
}

TEST_F(ControllerGizmoTest, ACutSparesTheLayersLeftOut) {
    // A ray through the middle of cube-in-cube with the middle cut away: with layers=all it
    // passes both cubes' near walls; with layers=1 the outer cube (layer 0) stands.
    auto controller = makeController();
    controller->addLens("clip", {0.5f, 0.5f});
    controller->setLensProperty(0, "box", "-1,-1,-1,2,2,2"); // everything under the lens
    controller->setLensProperty(0, "caps", "none");
    const glm::vec2 middle = pixelOf({0.5f, 0.5f});
    const glm::vec3 eye = controller->camera().eye();
    const float cutAll = glm::length(controller->pointUnder(middle) - eye);
    controller->setLensProperty(0, "layers", "1");
    const float sparedOuter = glm::length(controller->pointUnder(middle) - eye);
    controller->setLensEnabled(0, false);
    const float noLens = glm::length(controller->pointUnder(middle) - eye);
    EXPECT_NEAR(sparedOuter, noLens, 1e-4f) << "the outer cube is not cut";
    EXPECT_GT(cutAll, noLens + 1e-3f) << "without sparing, the ray goes past it";
}

} // namespace
} // namespace mvcl::test
