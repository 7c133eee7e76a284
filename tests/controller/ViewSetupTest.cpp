// ViewSetup: which scene, camera and layer rules a view gets from a request and a session file,
// and the world ↔ scene conversion of cameras.

#include <mvcl/testing/ErrorOf.h>
#include "controller/ControllerFixture.h"

#include <mvcl/controller/ViewCoordinates.h>
#include <mvcl/controller/ViewSetup.h>
#include <mvcl/io/SceneLoader.h>

#include <fstream>

namespace fs = std::filesystem;

namespace mvcl::test {
namespace {

class ViewSetupTest : public ControllerFixture {
protected:
    static fs::path writeSession(const std::string &json) {
        const fs::path file = scratchFolder() / "view.json";
        std::ofstream(file) << json;
        return file;
    }
};

TEST_F(ViewSetupTest, TheRequestsSceneWinsOverTheFilesAndItsLensesGoOnTop) {
    ViewRequest request;
    request.sessionFile = writeSession(R"({"scene": "builtin:onion", "lenses": [{"type": "achromatic"}]})");
    request.lensSpecs = {"layer:layers=2-"};
    ViewSetup setup = ViewSetup::prepare(request, *registry);
    EXPECT_EQ(setup.source, "builtin:onion");
    ASSERT_EQ(setup.session.lenses.size(), 2);
    EXPECT_EQ(setup.session.lenses.lens(0)->typeName(), "achromatic");
    EXPECT_EQ(setup.session.lenses.lens(1)->typeName(), "layer");

    request.source = "builtin:cube-in-cube";
    EXPECT_EQ(ViewSetup::prepare(request, *registry).source, "builtin:cube-in-cube");
}

TEST_F(ViewSetupTest, RequestRulesComeBeforeTheFilesSoTheyWin) {
    ViewRequest request;
    request.sessionFile = writeSession(R"({"scene": "builtin:onion", "layerRules": [{"match": "*", "layer": 3}]})");
    request.loadOptions.layerRules.add({"*skin*", 0});
    const ViewSetup setup = ViewSetup::prepare(request, *registry);
    ASSERT_EQ(setup.loadOptions.layerRules.rules().size(), 2u);
    EXPECT_EQ(setup.loadOptions.layerRules.rules()[0].pattern, "*skin*");
    EXPECT_EQ(setup.loadOptions.layerRules.match("skin", ""), 0);
    EXPECT_EQ(setup.loadOptions.layerRules.match("bone", ""), 3);
}

TEST_F(ViewSetupTest, ErrorsOfTheRequestNameItsOrigin) {
    ViewRequest request;
    request.source = "builtin:onion";
    request.lensSpecs = {"layer:strenght=1"};
    const std::string badSpec = errorOf([&] { ViewSetup::prepare(request, *registry); });
    EXPECT_EQ(badSpec.rfind("command line: --lens: ", 0), 0u) << badSpec;

    ViewRequest none;
    none.origin = "viewer";
    EXPECT_EQ(errorOf([&] { ViewSetup::prepare(none, *registry); }), "viewer: no scene given");
    none.sessionFile = writeSession(R"({"lenses": []})");
    EXPECT_NE(errorOf([&] { ViewSetup::prepare(none, *registry); }).find("names none"), std::string::npos);
}

TEST_F(ViewSetupTest, CameraComesFromTheRequestThenTheFileThenTheScene) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    ViewRequest request;
    request.source = "builtin:cube-in-cube";
    const ViewSetup plain = ViewSetup::prepare(request, *registry);
    EXPECT_EQ(plain.camera(scene, request, 4.f / 3.f), Camera::fromDesc(scene.cameras.front()))
        << "a built-in scene's own view";

    request.sessionFile = writeSession(R"({"camera": {"eye": [1, 2, 9], "target": [0, 1, 0], "fov": 30}})");
    const ViewSetup withFile = ViewSetup::prepare(request, *registry);
    const Camera fromFile = withFile.camera(scene, request, 4.f / 3.f);
    EXPECT_EQ(fromFile.eye(), glm::vec3(1.f, 2.f, 9.f));
    EXPECT_EQ(fromFile.verticalFovDegrees(), 30.f);

    request.eye = glm::vec3(0.f, 5.f, 5.f);
    request.verticalFovDegrees = 50.f;
    const Camera overridden = withFile.camera(scene, request, 4.f / 3.f);
    EXPECT_EQ(overridden.eye(), glm::vec3(0.f, 5.f, 5.f));
    EXPECT_EQ(overridden.target(), glm::vec3(0.f, 1.f, 0.f)) << "parts not given stay the file's";
    EXPECT_EQ(overridden.verticalFovDegrees(), 50.f);

    request.sceneCamera = "7";
    const std::string unknown = errorOf([&] { withFile.camera(scene, request, 1.f); });
    EXPECT_NE(unknown.find("command line: --camera '7'"), std::string::npos) << unknown;
}

TEST_F(ViewSetupTest, CamerasAreConvertedBetweenWorldAndSceneSpaceInOnePlace) {
    const ViewCoordinates coordinates({200, 100}, glm::dvec3(100.0, -50.0, 10.0));
    const LensStackCamera world{"", {101.f, -48.f, 20.f}, {100.f, -50.f, 10.f}, {0.f, 1.f, 0.f}, 35.f};
    const Camera camera = coordinates.cameraFromWorld(world);
    EXPECT_EQ(camera.eye(), glm::vec3(1.f, 2.f, 10.f));
    EXPECT_EQ(camera.target(), glm::vec3(0.f));
    EXPECT_EQ(coordinates.worldFromCamera(camera), world);
    EXPECT_EQ(coordinates.normalizedFromPixel({50.f, 50.f}), glm::vec2(0.25f, 0.5f));
    EXPECT_EQ(coordinates.pixelFromNormalized({0.25f, 0.5f}), glm::vec2(50.f, 50.f));
}

TEST_F(ViewSetupTest, DescribeGivesTheEffectiveSessionInWorldUnits) {
    ViewRequest request;
    request.sessionFile = writeSession(R"({"scene": "builtin:onion", "visibleLayers": "1-",
                                           "lenses": [{"type": "achromatic"}]})");
    request.loadOptions.layerRules.add({"*", 2});
    const ViewSetup setup = ViewSetup::prepare(request, *registry);
    const Scene scene = loadScene(setup.source, setup.loadOptions);
    const Camera camera = setup.camera(scene, request, 1.f);
    const LensStackDescription description = setup.describe(scene, camera);
    EXPECT_EQ(description.scene, "builtin:onion");
    ASSERT_TRUE(description.camera);
    EXPECT_EQ(description.camera->eye, ViewCoordinates({1, 1}, scene).worldFromScene(camera.eye()));
    EXPECT_EQ(description.layerRules.rules().size(), 1u);
    EXPECT_EQ(description.visibleLayers, layersFrom(1));
    EXPECT_EQ(description.lenses.size(), 1);
}

TEST_F(ViewSetupTest, TheFilesMemoryBudgetRefusesAModelAndTheRequestsWins) {
    const std::string engine = (fs::path(MVCL_TEST_DATA_DIR) / "models" / "2CylinderEngine" / "2CylinderEngine.glb").string();
    ViewRequest request;
    request.sessionFile = writeSession(R"({"scene": ")" + engine + R"(", "memoryBudgetMiB": 1})");
    const ViewSetup setup = ViewSetup::prepare(request, *registry);
    EXPECT_EQ(setup.loadOptions.memoryBudgetBytes, 1ull << 20);
    const std::string error = errorOf([&] { loadScene(setup.source, setup.loadOptions); });
    EXPECT_NE(error.find("more than the memory budget of 1 MiB"), std::string::npos) << error;
    // Kept when the session is written again.
    const Scene onion = loadScene("builtin:onion");
    const LensStackDescription described = setup.describe(onion, Camera::framing(onion.bounds(), 40.f, 1.f));
    EXPECT_EQ(described.memoryBudgetBytes, 1ull << 20);
    EXPECT_NE(lensStackJson(described).find("\"memoryBudgetMiB\": 1"), std::string::npos) << lensStackJson(described);

    request.loadOptions.memoryBudgetBytes = 1ull << 30; // --memory-budget 1024
    const ViewSetup roomy = ViewSetup::prepare(request, *registry);
    EXPECT_NO_THROW(loadScene(roomy.source, roomy.loadOptions));

    const std::string bad = errorOf([&] {
        ViewRequest broken;
        broken.sessionFile = writeSession(R"({"scene": "builtin:onion", "memoryBudgetMiB": 0.5})");
        ViewSetup::prepare(broken, *registry);
    });
    EXPECT_NE(bad.find("memoryBudgetMiB: expected a whole number of MiB ≥ 1, got 0.5"), std::string::npos) << bad;
}

} // namespace
} // namespace mvcl::test
