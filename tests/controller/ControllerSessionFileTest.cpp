// Controller session files: save → load round trip, broken files leave the state untouched
// with an error naming the file, the recovery copy (written, removed, offered, restored), dropped files.

#include <mvcl/testing/ErrorOf.h>
#include "controller/ControllerFixture.h"

#include <mvcl/io/LensStackFile.h>

#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace mvcl::test {
namespace {

class ControllerSessionFileTest : public ControllerFixture {
protected:
    /// A controller with a few edits of every kind.
    static std::unique_ptr<Controller> editedController() {
        auto controller = makeController();
        controller->addLens("layer", {0.4f, 0.45f});
        controller->setLensProperty(0, "layers", "1-");
        controller->setLensLabel(0, "reveal");
        controller->addLens("shadow", {0.6f, 0.5f});
        controller->setLensRegion(1, LensRegion::polygon({{0.5f, 0.4f}, {0.8f, 0.45f}, {0.7f, 0.8f}}));
        controller->setLensProperty(1, "mode", "tinted");
        controller->setLensEnabled(1, false);
        controller->setLayerVisibility(2, LayerVisibility::Hidden);
        controller->orbit(0.4f, 0.1f);
        return controller;
    }

    static std::string readText(const fs::path &file) {
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }
};

/// The session's contact tolerance reaches the scene the tracer is built from, is saved back, and
/// a session without one turns it off again (the scene is reloaded for it, as for new rules).
TEST_F(ControllerSessionFileTest, TheContactToleranceTravelsWithTheSession) {
    const fs::path with = scratchFolder() / "contact-session.json";
    std::ofstream(with) << R"({"version": 1, "scene": "builtin:cube-in-cube", "layerContact": {"relative": 0.0005}})";
    auto controller = makeController();
    EXPECT_FALSE(controller->scene().layerContact.isEnabled());
    controller->loadSession(with);
    const LayerContact expected{0.0005, LayerContact::Measure::RelativeToSceneSize};
    EXPECT_EQ(controller->scene().layerContact, expected);
    EXPECT_EQ(controller->description().layerContact, expected);
    const fs::path saved = scratchFolder() / "contact-saved.json";
    controller->saveSession(saved);
    EXPECT_NE(readText(saved).find("\"relative\": 0.0005"), std::string::npos) << readText(saved);

    const fs::path without = scratchFolder() / "no-contact-session.json";
    std::ofstream(without) << R"({"version": 1, "scene": "builtin:cube-in-cube"})";
    controller->loadSession(without);
    EXPECT_FALSE(controller->scene().layerContact.isEnabled());
}

TEST_F(ControllerSessionFileTest, SaveThenLoadGivesTheSameState) {
    const fs::path file = scratchFolder() / "session.json";
    auto edited = editedController();
    edited->saveSession(file);
    EXPECT_EQ(edited->sessionPath(), file);
    EXPECT_NE(readText(file).find("\"visibleLayers\": \"0-1,3-\""), std::string::npos) << readText(file);

    auto fresh = makeController();
    fresh->addLens("magnifier", {0.5f, 0.5f});
    fresh->loadSession(file);
    EXPECT_EQ(fresh->state(), edited->state());
    EXPECT_EQ(fresh->sceneSource(), "builtin:cube-in-cube");
    EXPECT_EQ(fresh->sessionPath(), file);
    EXPECT_FALSE(fresh->canUndo()) << "a loaded session starts a new history";
    EXPECT_EQ(fresh->renderSession().camera(), fresh->camera());

    // The same file read by the framework's reader (as mvcl-render does) is the description.
    EXPECT_EQ(readLensStackFile(file, *registry), fresh->description());
}

TEST_F(ControllerSessionFileTest, ABrokenSessionThrowsNamingTheFileAndChangesNothing) {
    const fs::path folder = scratchFolder();
    auto controller = editedController();
    const SessionState before = controller->state();
    const int steps = controller->undoCount();
    const struct {
        const char *json;
        const char *problem;
    } cases[] = {
        {R"({"scene": "builtin:cube-in-cube", "zoom": 2})", "unknown key 'zoom'"},
        {R"({"lenses": [{"type": "shadow", "properties": {"strenght": 1}}]})", "strenght"},
        {R"({"lenses": [)", "invalid JSON"},
        {R"({"scene": "builtin:teapot"})", "teapot"},
        {R"({"scene": "builtin:cube-in-cube", "visibleLayers": "0-40"})", "visibleLayers"},
        {R"({"lenses": []})", "no scene"},
    };
    for (const auto &c : cases) {
        const fs::path file = folder / "broken.json";
        std::ofstream(file) << c.json;
        const std::string message = errorOf([&] { controller->loadSession(file); });
        EXPECT_NE(message.find("broken.json"), std::string::npos) << c.json << "\n" << message;
        EXPECT_NE(message.find(c.problem), std::string::npos) << c.json << "\n" << message;
        EXPECT_EQ(controller->state(), before) << c.json;
        EXPECT_EQ(controller->undoCount(), steps) << c.json;
        EXPECT_TRUE(controller->sessionPath().empty()) << c.json;
    }
    const std::string missing = errorOf([&] { controller->loadSession(folder / "missing.json"); });
    EXPECT_NE(missing.find("missing.json"), std::string::npos) << missing;
    EXPECT_EQ(controller->state(), before);
}

TEST_F(ControllerSessionFileTest, WithoutAnIntervalTheRecoveryCopyIsRewrittenAfterEveryEditStep) {
    const fs::path folder = scratchFolder();
    auto controller = makeController();
    controller->setRecoveryInterval(std::chrono::milliseconds(0));
    EXPECT_TRUE(controller->recoveryPath().empty()) << "no session, no recovery path given";
    controller->saveSession(folder / "work.json");
    EXPECT_EQ(controller->recoveryPath(), folder / "work.recovery.json");
    EXPECT_FALSE(fs::exists(controller->recoveryPath())) << "saving leaves nothing to recover";
    EXPECT_FALSE(controller->hasUnsavedChanges());

    controller->addLens("achromatic", {0.3f, 0.3f});
    ASSERT_TRUE(fs::exists(folder / "work.recovery.json"));
    EXPECT_EQ(readLensStackFile(folder / "work.recovery.json", *registry), controller->description());
    EXPECT_TRUE(controller->hasUnsavedChanges());

    drag(*controller, pixelOf({0.3f, 0.3f}), pixelOf({0.3f, 0.3f}) + glm::vec2(20.f, 20.f));
    EXPECT_EQ(readLensStackFile(folder / "work.recovery.json", *registry), controller->description());
    controller->undo();
    EXPECT_EQ(readLensStackFile(folder / "work.recovery.json", *registry), controller->description());

    // A recovery copy loads as a session: a crash loses nothing.
    auto restored = makeController();
    restored->loadSession(folder / "work.recovery.json");
    EXPECT_EQ(restored->state(), controller->state());

    const fs::path chosen = folder / "elsewhere" / "copy.json";
    controller->setRecoveryPath(chosen);
    controller->setLayerVisibility(0, LayerVisibility::Hidden);
    EXPECT_EQ(readLensStackFile(chosen, *registry), controller->description());
}

TEST_F(ControllerSessionFileTest, DragMovesReachTheRecoveryCopyBeforeTheRelease) {
    const fs::path folder = scratchFolder();
    auto controller = makeController();
    controller->setRecoveryInterval(std::chrono::milliseconds(0));
    controller->addLens("achromatic", {0.3f, 0.5f});
    controller->saveSession(folder / "work.json");
    const glm::vec2 from = pixelOf({0.3f, 0.5f});
    controller->handle(InputEvent::pointerPress(from, PointerButton::Left));
    controller->handle(InputEvent::pointerMove(from + glm::vec2(16.f, 0.f)));
    EXPECT_FALSE(fs::exists(folder / "work.recovery.json")) << "written once a frame, not inside an event";
    controller->updateRecovery(); // the frame after the move
    ASSERT_TRUE(fs::exists(folder / "work.recovery.json"));
    const LensStackDescription midDrag = readLensStackFile(folder / "work.recovery.json", *registry);
    EXPECT_NEAR(midDrag.lenses.lens(0)->region().center().x, 0.4f, 1e-4f);
    controller->handle(InputEvent::pointerRelease(from + glm::vec2(16.f, 0.f), PointerButton::Left));
}

TEST_F(ControllerSessionFileTest, SavingRemovesTheCopyAndACleanExitKeepsOnlyUnsavedChanges) {
    const fs::path folder = scratchFolder();
    const fs::path copy = folder / "work.recovery.json";
    auto controller = makeController();
    controller->setRecoveryInterval(std::chrono::hours(1)); // no write falls due by itself
    controller->saveSession(folder / "work.json");
    controller->addLens("achromatic", {0.3f, 0.5f}); // the first change is written at once
    ASSERT_TRUE(fs::exists(copy));
    controller->setLensLabel(0, "second"); // within the interval: pending
    EXPECT_NE(readLensStackFile(copy, *registry).lenses.lens(0)->label(), "second");
    controller->finishRecovery(); // a clean exit with unsaved changes: the last one lands
    EXPECT_EQ(readLensStackFile(copy, *registry).lenses.lens(0)->label(), "second");

    controller->saveSession(folder / "work.json");
    EXPECT_FALSE(fs::exists(copy)) << "saved: nothing to recover";
    EXPECT_FALSE(controller->hasRecovery());
    controller->finishRecovery();
    EXPECT_FALSE(fs::exists(copy)) << "a clean exit without unsaved changes leaves no copy";

    // Saved under another name: the copy of the old name goes too.
    controller->setLensLabel(0, "third");
    controller->finishRecovery();
    ASSERT_TRUE(fs::exists(copy));
    controller->saveSession(folder / "renamed.json");
    EXPECT_FALSE(fs::exists(copy));
}

TEST_F(ControllerSessionFileTest, ARecoveryCopyNewerThanItsSessionIsOfferedAndRestoresTheLenses) {
    const fs::path folder = scratchFolder();
    const fs::path session = folder / "work.json", copy = folder / "work.recovery.json";
    {
        auto crashed = makeController();
        crashed->saveSession(session);
        crashed->addLens("achromatic", {0.3f, 0.5f});
        crashed->addLens("shadow", {0.6f, 0.5f});
        crashed->finishRecovery(); // stands in for the last write before a crash
    }
    fs::last_write_time(copy, fs::last_write_time(session) + std::chrono::seconds(5));
    ViewRequest request;
    request.sessionFile = session;
    auto controller = makeController(request);
    EXPECT_EQ(controller->lensCount(), 0);
    EXPECT_TRUE(controller->hasRecovery());
    EXPECT_FALSE(controller->hasUnsavedChanges()) << "opening is not a change";

    controller->restoreRecovery();
    EXPECT_EQ(controller->lensCount(), 2);
    EXPECT_EQ(controller->sessionPath(), session) << "still the user's session";
    EXPECT_EQ(controller->recoveryPath(), copy);
    EXPECT_TRUE(controller->hasUnsavedChanges()) << "restored, not saved";
    controller->finishRecovery();
    EXPECT_TRUE(fs::exists(copy)) << "a clean exit keeps the restored state until it is saved";

    auto declined = makeController(request);
    ASSERT_TRUE(declined->hasRecovery());
    declined->discardRecovery();
    EXPECT_FALSE(fs::exists(copy));
    EXPECT_FALSE(declined->hasRecovery());

    // A copy older than its session: saved since, nothing to offer.
    std::ofstream(copy) << R"({"scene": "builtin:cube-in-cube", "lenses": []})";
    fs::last_write_time(copy, fs::last_write_time(session) - std::chrono::seconds(5));
    EXPECT_FALSE(makeController(request)->hasRecovery());
}

TEST_F(ControllerSessionFileTest, AFailedRecoveryWriteGoesToTheErrorCallback) {
    auto controller = makeController();
    controller->setRecoveryPath("/proc/forbidden/recovery.json");
    std::vector<std::string> errors;
    controller->setErrorCallback([&](const Error &e) { errors.emplace_back(e.what()); });
    controller->addLens("layer", {0.5f, 0.5f});
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("/proc/forbidden/recovery.json"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("recovery copy not written"), std::string::npos) << errors[0];
    EXPECT_EQ(controller->lensCount(), 1) << "the edit stands";
}

TEST_F(ControllerSessionFileTest, DroppedFilesOpenSessionsAndModelsAndReportBrokenOnes) {
    const fs::path folder = scratchFolder();
    auto edited = editedController();
    edited->saveSession(folder / "dropped.json");

    auto controller = makeController();
    std::vector<std::string> errors;
    controller->setErrorCallback([&](const Error &e) { errors.emplace_back(e.what()); });
    int sceneChanges = 0;
    controller->setSceneChangedCallback([&] { ++sceneChanges; });
    EXPECT_TRUE(controller->handle(InputEvent::fileDrop({10.f, 10.f}, {(folder / "dropped.json").string()})));
    EXPECT_EQ(controller->state(), edited->state());
    EXPECT_EQ(sceneChanges, 0) << "the same scene is kept";

    std::ofstream(folder / "bad.json") << R"({"lenses": [{"type": "nosuchlens"}]})";
    const SessionState before = controller->state();
    EXPECT_FALSE(controller->handle(InputEvent::fileDrop({10.f, 10.f}, {(folder / "bad.json").string()})));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("bad.json"), std::string::npos) << errors[0];
    EXPECT_EQ(controller->state(), before);

    const fs::path box = fs::path(MVCL_TEST_DATA_DIR) / "models" / "Box" / "Box.glb";
    EXPECT_TRUE(controller->handle(InputEvent::fileDrop({10.f, 10.f}, {box.string()})));
    EXPECT_EQ(sceneChanges, 1);
    EXPECT_EQ(controller->sceneSource(), box.string());
    EXPECT_EQ(controller->lensCount(), 2) << "the lenses stay with a new model";
    EXPECT_EQ(controller->visibleLayers(), kAllLayers);
    EXPECT_EQ(controller->renderSession().camera(), controller->camera());
    EXPECT_FALSE(controller->canUndo());
}

TEST_F(ControllerSessionFileTest, SeveralDroppedModelsAreLayersAndTheSessionKeepsTheList) {
    const fs::path kidney = fs::path(MVCL_TEST_DATA_DIR) / "meshes" / "kidney";
    const std::vector<std::string> files = {(kidney / "kidney-capsule.stl").string(),
                                            (kidney / "renal-pyramids.ply").string()};
    auto controller = makeController();
    EXPECT_TRUE(controller->handle(InputEvent::fileDrop({10.f, 10.f}, files)));
    EXPECT_EQ(controller->sceneSources(), files);
    ASSERT_EQ(controller->scene().layers.count(), 2);
    EXPECT_EQ(controller->scene().layers.find(1)->name, "renal-pyramids");

    const fs::path session = scratchFolder() / "two-files.json";
    controller->saveSession(session);
    EXPECT_NE(readText(session).find("\"scene\": ["), std::string::npos) << readText(session);
    auto reopened = makeController();
    reopened->loadSession(session);
    ASSERT_EQ(reopened->sceneSources().size(), 2u);
    EXPECT_TRUE(fs::equivalent(reopened->sceneSources()[1], files[1]));
    EXPECT_EQ(reopened->scene().layers.find(0)->name, "kidney-capsule");
    EXPECT_EQ(reopened->scene().triangleCount(), controller->scene().triangleCount());
}

TEST_F(ControllerSessionFileTest, WithoutAnErrorCallbackHandleThrows) {
    auto controller = makeController();
    EXPECT_THROW(controller->handle(InputEvent::fileDrop({0.f, 0.f}, {"/nonexistent/model.glb"})), Error);
}

} // namespace
} // namespace mvcl::test
