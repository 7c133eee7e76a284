// SceneLoadJob: the scene as read first (renderable at once), then the inferred one, both with
// tracers that answer as fresh builds; errors and cancelling.

#include <mvcl/io/SceneLoadJob.h>

#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include "../tracer/TracerTestUtil.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

using namespace mvcl;

namespace {

const std::filesystem::path kModels = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";

std::vector<std::string> engine() { return {(kModels / "2CylinderEngine" / "2CylinderEngine.glb").string()}; }

/// Every result the job hands out, in order, until it finishes.
std::vector<SceneLoadJob::Result> allResults(SceneLoadJob &job) {
    std::vector<SceneLoadJob::Result> results;
    while (!job.isFinished()) {
        if (auto r = job.takeResult()) results.push_back(std::move(*r));
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (auto r = job.takeResult()) results.push_back(std::move(*r));
    return results;
}

/// The job's first result, taken as a display loop would, as soon as it comes.
SceneLoadJob::Result firstResultOf(SceneLoadJob &job) {
    std::optional<SceneLoadJob::Result> first;
    while (!first && !job.isFinished()) {
        first = job.takeResult();
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    EXPECT_TRUE(first.has_value()) << job.progressText();
    return first.value_or(SceneLoadJob::Result{});
}

} // namespace

TEST(SceneLoadJob, HandsOutTheSceneAsReadThenTheInferredOne) {
    SceneLoadJob job(engine(), {});
    // The first result is the scene as read.
    const SceneLoadJob::Result first = firstResultOf(job);
    ASSERT_TRUE(first.scene);
    EXPECT_FALSE(first.layersAreFinal);
    EXPECT_EQ(first.scene->layers.count(), 1);
    EXPECT_EQ(&first.tracer->scene(), first.scene.get());
    job.wait();
    EXPECT_EQ(job.stage(), SceneLoadJob::Stage::Done);
    const std::optional<SceneLoadJob::Result> last = job.takeResult();
    ASSERT_TRUE(last.has_value());
    EXPECT_TRUE(last->layersAreFinal);
    EXPECT_FALSE(job.takeResult().has_value());

    const Scene alone = loadScene(engine());
    ASSERT_EQ(last->scene->meshes.size(), alone.meshes.size());
    for (std::size_t i = 0; i < alone.meshes.size(); ++i) EXPECT_EQ(last->scene->meshes[i].layer, alone.meshes[i].layer);
    EXPECT_EQ(last->scene->layers.count(), alone.layers.count());
    EXPECT_EQ(&last->tracer->scene(), last->scene.get());
    test::expectSameClosestHits(*last->tracer, Tracer(*last->scene));
    // The first result is untouched by the inference that ran beside it.
    for (const TriangleMesh &m : first.scene->meshes) EXPECT_EQ(m.layerSource, LayerSource::Unassigned);
    test::expectSameClosestHits(*first.tracer, Tracer(*first.scene));
}

TEST(SceneLoadJob, NothingToInferGivesOneFinalResult) {
    SceneLoadJob job({"builtin:cube-in-cube"}, {});
    const std::vector<SceneLoadJob::Result> results = allResults(job);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_TRUE(results[0].layersAreFinal);
    EXPECT_EQ(results[0].scene->layers.count(), loadScene("builtin:cube-in-cube").layers.count());
    EXPECT_EQ(job.progressText(), "done");
}

TEST(SceneLoadJob, LateTakerGetsOnlyTheLastResult) {
    SceneLoadJob job(engine(), {});
    job.wait();
    const std::optional<SceneLoadJob::Result> r = job.takeResult();
    ASSERT_TRUE(r.has_value());
    EXPECT_TRUE(r->layersAreFinal);
    EXPECT_FALSE(job.takeResult().has_value());
}

TEST(SceneLoadJob, ABadFileFailsWithItsNameAndNoResult) {
    const std::filesystem::path bad = std::filesystem::temp_directory_path() / "mvcl-load-job-bad.glb";
    std::ofstream(bad, std::ios::binary) << "glTF but not really";
    SceneLoadJob job({bad.string()}, {});
    job.wait();
    EXPECT_EQ(job.stage(), SceneLoadJob::Stage::Failed);
    ASSERT_TRUE(job.error().has_value());
    EXPECT_NE(std::string(job.error()->what()).find(bad.string()), std::string::npos) << job.error()->what();
    EXPECT_EQ(job.progressText(), job.error()->what());
    EXPECT_FALSE(job.takeResult().has_value());
    std::filesystem::remove(bad);
}

TEST(SceneLoadJob, CancelStopsAndHandsOutNothingMore) {
    SceneLoadJob job(engine(), {});
    job.cancel();
    job.wait();
    EXPECT_EQ(job.stage(), SceneLoadJob::Stage::Done);
    EXPECT_FALSE(job.takeResult().has_value());
    // Destroying a job in flight waits for its thread without a crash.
    { SceneLoadJob dropped(engine(), {}); }
}

TEST(SceneLoadJob, WhenReleasedInfersOnlyAfterReleaseInference) {
    SceneLoadJob job(engine(), {}, SceneLoadJob::InferenceStart::WhenReleased);
    const SceneLoadJob::Result first = firstResultOf(job);
    ASSERT_TRUE(first.scene);
    EXPECT_FALSE(first.layersAreFinal);
    // Held: longer than the whole inference takes, nothing more comes.
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    EXPECT_EQ(job.stage(), SceneLoadJob::Stage::InferringLayers);
    EXPECT_FALSE(job.takeResult().has_value());
    job.releaseInference();
    job.wait();
    const std::optional<SceneLoadJob::Result> last = job.takeResult();
    ASSERT_TRUE(last.has_value());
    EXPECT_TRUE(last->layersAreFinal);
    EXPECT_GT(last->scene->layers.count(), 1);

    // Cancelled while held: the job ends without inferring.
    SceneLoadJob held(engine(), {}, SceneLoadJob::InferenceStart::WhenReleased);
    while (held.stage() != SceneLoadJob::Stage::InferringLayers && !held.isFinished())
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    held.cancel();
    held.wait();
    EXPECT_EQ(held.stage(), SceneLoadJob::Stage::Done);
    EXPECT_FALSE(held.takeResult().has_value());
}

TEST(SceneLoadJob, AQuickBvhFirstThenTheFullOneWithTheInferredLayers) {
    SceneLoadJob job(engine(), {}, SceneLoadJob::InferenceStart::WhenReleased, SceneLoadJob::FirstBvh::Quick);
    const SceneLoadJob::Result first = firstResultOf(job);
    ASSERT_TRUE(first.tracer);
    EXPECT_EQ(first.tracer->buildStats().bvhQuality, BvhQuality::Quick);
    EXPECT_FALSE(first.layersAreFinal);
    EXPECT_EQ(job.stage(), SceneLoadJob::Stage::RefiningBvh);
    EXPECT_EQ(job.progressText(), "building the full BVH");
    test::expectSameClosestHits(*first.tracer, Tracer(*first.scene));
    job.releaseInference();
    job.wait();
    const std::optional<SceneLoadJob::Result> last = job.takeResult();
    ASSERT_TRUE(last.has_value());
    EXPECT_TRUE(last->layersAreFinal);
    EXPECT_EQ(last->tracer->buildStats().bvhQuality, BvhQuality::Full);
    EXPECT_EQ(last->scene->layers.count(), loadScene(engine()).layers.count());
    test::expectSameClosestHits(*last->tracer, Tracer(*last->scene));
}

TEST(SceneLoadJob, NothingToInferOnAQuickBvhGivesTheSameSceneOnTheFullOneNext) {
    SceneLoadJob job({"builtin:cube-in-cube"}, {}, SceneLoadJob::InferenceStart::WhenReleased,
                     SceneLoadJob::FirstBvh::Quick);
    const SceneLoadJob::Result first = firstResultOf(job);
    ASSERT_TRUE(first.tracer);
    EXPECT_TRUE(first.layersAreFinal);
    EXPECT_EQ(first.tracer->buildStats().bvhQuality, BvhQuality::Quick);
    job.releaseInference();
    job.wait();
    const std::optional<SceneLoadJob::Result> last = job.takeResult();
    ASSERT_TRUE(last.has_value());
    EXPECT_TRUE(last->layersAreFinal);
    EXPECT_EQ(last->scene, first.scene);
    EXPECT_EQ(last->tracer->buildStats().bvhQuality, BvhQuality::Full);
    EXPECT_EQ(job.progressText(), "done");
}

TEST(SceneLoadJob, SmallScenesGetOneFullBuild) {
    // The engine (121k triangles) is below kQuickBvhFromTriangles: its first result is full.
    static_assert(SceneLoadJob::kQuickBvhFromTriangles > 121496);
    SceneLoadJob job(engine(), {}, SceneLoadJob::InferenceStart::WhenReleased);
    const SceneLoadJob::Result first = firstResultOf(job);
    ASSERT_TRUE(first.tracer);
    EXPECT_EQ(first.tracer->buildStats().bvhQuality, BvhQuality::Full);
    job.cancel();
}
