// Renaming layers: one undo step, shown in the scene's layer table, saved in the session file
// ("layerNames") and read back, bad layers and names refused without a change.

#include <mvcl/testing/ErrorOf.h>
#include "controller/ControllerFixture.h"

#include <mvcl/controller/ViewSetup.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/SceneLoader.h>

#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace mvcl::test {
namespace {

class ControllerLayerNamesTest : public ControllerFixture {};

TEST_F(ControllerLayerNamesTest, ARenameIsOneUndoStepShownBesideTheSharedScene) {
    auto controller = makeController();
    ASSERT_EQ(controller->layerName(1), "inner cube");
    controller->setLayerName(1, "kidney capsule");
    EXPECT_EQ(controller->layerName(1), "kidney capsule");
    EXPECT_EQ(controller->scene().layers.find(1)->name, "inner cube") << "the shared scene keeps its names";
    EXPECT_EQ(controller->state().layerNames, (std::map<int, std::string>{{1, "kidney capsule"}}));
    EXPECT_EQ(controller->undoCount(), 1);
    controller->setLayerName(1, "kidney capsule");
    EXPECT_EQ(controller->undoCount(), 1) << "the same name again changes nothing";

    controller->undo();
    EXPECT_EQ(controller->layerName(1), "inner cube");
    EXPECT_TRUE(controller->state().layerNames.empty());
    controller->redo();
    EXPECT_EQ(controller->layerName(1), "kidney capsule");

    controller->setLayerName(1, ""); // back to the scene's own name
    EXPECT_EQ(controller->layerName(1), "inner cube");
    EXPECT_TRUE(controller->state().layerNames.empty());
    EXPECT_EQ(controller->layerName(0), "outside") << "other layers untouched";
}

TEST_F(ControllerLayerNamesTest, BadLayersAndNamesAreRefusedWithoutAChange) {
    auto controller = makeController();
    const SessionState before = controller->state();
    const std::string missing = errorOf([&] { controller->setLayerName(7, "bone"); });
    EXPECT_NE(missing.find("layer 7: the scene has no such layer (it has 2)"), std::string::npos) << missing;
    EXPECT_NE(errorOf([&] { controller->setLayerName(-1, "x"); }).find("no such layer"), std::string::npos);
    const std::string twoLines = errorOf([&] { controller->setLayerName(0, "skin\nbone"); });
    EXPECT_NE(twoLines.find("layer 0: a layer name is one line"), std::string::npos) << twoLines;
    EXPECT_EQ(controller->state(), before);
    EXPECT_EQ(controller->undoCount(), 0);
}

TEST_F(ControllerLayerNamesTest, NamesTravelWithTheSessionFileAndItsRecoveryCopy) {
    const fs::path folder = scratchFolder();
    auto controller = makeController();
    controller->setRecoveryInterval(std::chrono::milliseconds(0));
    controller->saveSession(folder / "named.json");
    controller->setLayerName(0, "skin");
    EXPECT_EQ(readLensStackFile(folder / "named.recovery.json", *registry).layerNames,
              (std::map<int, std::string>{{0, "skin"}}));
    controller->saveSession(folder / "named.json");
    std::ifstream in(folder / "named.json");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find(R"("layerNames": {)"), std::string::npos) << text.str();

    ViewRequest request;
    request.sessionFile = folder / "named.json";
    auto reopened = makeController(request);
    EXPECT_EQ(reopened->layerName(0), "skin");
    EXPECT_EQ(reopened->layerName(1), "inner cube");
    EXPECT_EQ(reopened->undoCount(), 0);
    auto loaded = makeController();
    loaded->loadSession(folder / "named.json"); // the same scene: names applied without a reload
    EXPECT_EQ(loaded->layerName(0), "skin");
    EXPECT_EQ(loaded->description(), controller->description());
}

/// mvcl-render's way (ViewSetup without a Controller): the names reach the scene it renders and
/// prints, and --save-lenses keeps them.
TEST_F(ControllerLayerNamesTest, ViewSetupRenamesTheLayersOfTheSceneItLoads) {
    const fs::path file = scratchFolder() / "named.json";
    std::ofstream(file) << R"({"scene": "builtin:cube-in-cube", "layerNames": {"0": "skin", "5": "absent"}})";
    ViewRequest request;
    request.sessionFile = file;
    const ViewSetup setup = ViewSetup::prepare(request, *registry);
    Scene scene = loadScene(setup.sources(), setup.loadOptions);
    setup.renameLayers(scene);
    EXPECT_EQ(scene.layers.find(0)->name, "skin");
    EXPECT_EQ(scene.layers.find(1)->name, "inner cube");
    EXPECT_EQ(scene.layers.find(5), nullptr) << "a name does not make a layer";
    EXPECT_EQ(setup.describe(scene, setup.camera(scene, request, 1.f)).layerNames.at(0), "skin");
}

TEST_F(ControllerLayerNamesTest, BrokenLayerNamesInASessionFileNameTheKey) {
    const fs::path file = scratchFolder() / "broken.json";
    const struct {
        const char *names, *problem;
    } cases[] = {
        {R"([1, 2])", "layerNames: expected an object of layer number"},
        {R"({"x": "skin"})", "layerNames.x: a layer number 0..31 is expected"},
        {R"({"32": "skin"})", "layerNames.32: a layer number 0..31 is expected"},
        {R"({"1": ""})", "layerNames.1: a layer name must not be empty"},
        {R"({"1": 3})", "layerNames.1"},
    };
    for (const auto &c : cases) {
        std::ofstream(file) << R"({"scene": "builtin:cube-in-cube", "layerNames": )" << c.names << "}";
        const std::string error = errorOf([&] { readLensStackFile(file, *registry); });
        EXPECT_NE(error.find(c.problem), std::string::npos) << c.names << "\n" << error;
        EXPECT_EQ(error.rfind(file.string(), 0), 0u) << error;
    }
}

} // namespace
} // namespace mvcl::test
