// LoadedScene: one BVH per load, and the same scene as loadScene() infers by itself.

#include <mvcl/io/LoadedScene.h>

#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include "../tracer/TracerTestUtil.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

using namespace mvcl;

namespace {

const std::filesystem::path kModels = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";

void expectSameLayers(const Scene &a, const Scene &b) {
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (std::size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].layer, b.meshes[i].layer) << a.meshes[i].name;
        EXPECT_EQ(a.meshes[i].layerSource, b.meshes[i].layerSource) << a.meshes[i].name;
        EXPECT_EQ(a.meshes[i].layerConfidence, b.meshes[i].layerConfidence) << a.meshes[i].name;
    }
    ASSERT_EQ(a.layers.layers().size(), b.layers.layers().size());
    for (std::size_t i = 0; i < a.layers.layers().size(); ++i) {
        EXPECT_EQ(a.layers.layers()[i].id, b.layers.layers()[i].id);
        EXPECT_EQ(a.layers.layers()[i].name, b.layers.layers()[i].name);
    }
}


} // namespace

TEST(LoadedScene, InfersTheLayersLoadSceneInfersWithOneBvh) {
    // Several parts to peel: inference runs on the load's own tracer, which then moves onto the
    // inferred layers.
    const std::vector<std::string> sources{(kModels / "2CylinderEngine" / "2CylinderEngine.glb").string()};
    const Scene alone = loadScene(sources);
    const LoadedScene loaded = LoadedScene::load(sources);
    expectSameLayers(*loaded.scene, alone);
    EXPECT_GT(alone.layers.count(), 1);
    EXPECT_GT(loaded.scene->report.inferenceMilliseconds, 0.0);
    EXPECT_GT(loaded.readMilliseconds, 0.0);
    EXPECT_EQ(&loaded.tracer->scene(), loaded.scene.get());
    const Tracer fresh(*loaded.scene);
    test::expectSameClosestHits(*loaded.tracer, fresh);
}

TEST(LoadedScene, BuiltinScenesAndRulesKeepTheirLayers) {
    const std::vector<std::string> builtin{"builtin:cube-in-cube"};
    expectSameLayers(*LoadedScene::load(builtin).scene, loadScene(builtin));

    // A rule places the meshes it matches and names the layer; inference places the rest.
    SceneLoadOptions options;
    options.layerRules.add(LayerRule("*Piston*", 5, "pistons"));
    const std::vector<std::string> sources{(kModels / "2CylinderEngine" / "2CylinderEngine.glb").string()};
    const LoadedScene loaded = LoadedScene::load(sources, options);
    expectSameLayers(*loaded.scene, loadScene(sources, options));
    ASSERT_NE(loaded.scene->layers.find(5), nullptr);
    EXPECT_EQ(loaded.scene->layers.find(5)->name, "pistons");
}

TEST(LoadedScene, ByCallerLeavesTheInferenceToFinishLayers) {
    SceneLoadOptions options;
    options.inferenceTiming = LayerInferenceTiming::ByCaller;
    const std::vector<std::string> sources{(kModels / "2CylinderEngine" / "2CylinderEngine.glb").string()};
    Scene scene = loadScene(sources, options);
    for (const TriangleMesh &m : scene.meshes) EXPECT_EQ(m.layerSource, LayerSource::Unassigned);
    EXPECT_EQ(scene.layers.count(), 1);
    // Inference on a copy while the first tracer (over `scene`) stays valid for others.
    const Tracer first(scene);
    Scene inferred = scene;
    EXPECT_TRUE(finishLayers(inferred, first, options));
    expectSameLayers(inferred, loadScene(sources));
    for (const TriangleMesh &m : scene.meshes) EXPECT_EQ(m.layerSource, LayerSource::Unassigned);
    const Tracer moved(inferred, first);
    test::expectSameClosestHits(moved, Tracer(inferred));
    // Nothing left to infer: nothing moves.
    EXPECT_FALSE(finishLayers(inferred, moved, options));
}
