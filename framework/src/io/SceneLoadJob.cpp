#include <mvcl/io/SceneLoadJob.h>

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace mvcl {

struct SceneLoadJob::Private {
    std::vector<std::string> sources;
    SceneLoadOptions options;

    mutable std::mutex mutex;
    std::condition_variable finished;
    Stage stage = Stage::Reading;
    std::string detail;                 ///< what the stage works on, for progressText()
    std::optional<Result> ready;        ///< the newest result not yet taken
    std::optional<Error> failure;
    std::atomic<bool> cancelled{false};
    FirstBvh firstBvh = FirstBvh::QuickWhenLarge;
    bool inferenceReleased = true; ///< false until releaseInference() for InferenceStart::WhenReleased
    std::condition_variable released;
    std::thread thread;

    void setStage(Stage s, std::string text = {}) {
        std::lock_guard lock(mutex);
        stage = s;
        detail = std::move(text);
    }
    void publish(Result result, Stage next) {
        std::lock_guard lock(mutex);
        if (cancelled) return;
        ready = std::move(result);
        stage = next;
        detail.clear();
    }
    void finish(Stage s, std::optional<Error> error = std::nullopt) {
        {
            std::lock_guard lock(mutex);
            if (s == Stage::Failed || stage != Stage::Failed) stage = s;
            failure = std::move(error);
        }
        finished.notify_all();
    }

    void run();
};

void SceneLoadJob::Private::run() {
    try {
        setStage(Stage::Reading, describeSources(sources));
        SceneLoadOptions byJob = options;
        byJob.inferenceTiming = LayerInferenceTiming::ByCaller;
        auto scene = std::make_shared<Scene>(loadScene(sources, byJob));
        if (cancelled) return finish(Stage::Done);

        std::size_t triangles = 0;
        for (const TriangleMesh &m : scene->meshes) triangles += m.indices.size();
        const bool quickFirst = firstBvh == FirstBvh::Quick ||
                                (firstBvh == FirstBvh::QuickWhenLarge && triangles >= kQuickBvhFromTriangles);
        setStage(Stage::BuildingBvh, std::to_string(triangles));
        TracerSettings first;
        first.bvhQuality = quickFirst ? BvhQuality::Quick : BvhQuality::Full;
        std::shared_ptr<const Tracer> tracer = std::make_shared<const Tracer>(*scene, first);
        if (cancelled) return finish(Stage::Done);

        const bool toInfer = std::any_of(scene->meshes.begin(), scene->meshes.end(), [](const TriangleMesh &m) {
            return m.layerSource == LayerSource::Unassigned;
        });
        // Only names to give: done before anyone else sees the scene.
        if (!toInfer) finishLayers(*scene, *tracer, options);
        if (!toInfer && !quickFirst) {
            publish(Result{scene, tracer, true}, Stage::Done);
            return finish(Stage::Done);
        }
        // The first scene is shared from here on: inference works on a copy.
        publish(Result{scene, tracer, !toInfer}, quickFirst ? Stage::RefiningBvh : Stage::InferringLayers);
        {
            std::unique_lock lock(mutex);
            released.wait(lock, [this] { return inferenceReleased || cancelled; });
        }
        if (cancelled) return finish(Stage::Done);
        if (quickFirst) {
            // The full build, over the same scene: the first result's sessions keep querying
            // the quick tracer meanwhile (queries are const and thread-safe).
            tracer = std::make_shared<const Tracer>(*scene);
            if (cancelled) return finish(Stage::Done);
            if (!toInfer) {
                publish(Result{scene, tracer, true}, Stage::Done);
                return finish(Stage::Done);
            }
            setStage(Stage::InferringLayers);
        }
        auto inferred = std::make_shared<Scene>(*scene);
        finishLayers(*inferred, *tracer, options);
        if (cancelled) return finish(Stage::Done);
        // A tracer over the copy even when no mesh moved: the copy has the layers' names.
        auto final = std::make_shared<const Tracer>(*inferred, *tracer);
        publish(Result{inferred, final, true}, Stage::Done);
        finish(Stage::Done);
    } catch (const Error &e) {
        finish(Stage::Failed, e);
    } catch (const std::bad_alloc &) {
        finish(Stage::Failed, Error(describeSources(sources), "out of memory while loading"));
    } catch (const std::exception &e) {
        finish(Stage::Failed, Error(describeSources(sources), e.what()));
    }
}

SceneLoadJob::SceneLoadJob(std::vector<std::string> sources, SceneLoadOptions options, InferenceStart inferenceStart,
                           FirstBvh firstBvh)
    : d(std::make_unique<Private>()) {
    d->sources = std::move(sources);
    d->options = std::move(options);
    d->firstBvh = firstBvh;
    d->inferenceReleased = inferenceStart == InferenceStart::AtOnce;
    d->thread = std::thread([p = d.get()] { p->run(); });
}

SceneLoadJob::~SceneLoadJob() {
    cancel();
    if (d->thread.joinable()) d->thread.join();
}

SceneLoadJob::Stage SceneLoadJob::stage() const {
    std::lock_guard lock(d->mutex);
    return d->stage;
}

std::string SceneLoadJob::progressText() const {
    std::lock_guard lock(d->mutex);
    switch (d->stage) {
    case Stage::Reading: return "reading " + d->detail;
    case Stage::BuildingBvh: return "building the BVH of " + d->detail + " triangles";
    case Stage::RefiningBvh: return "building the full BVH";
    case Stage::InferringLayers: return "inferring layers";
    case Stage::Done: return "done";
    case Stage::Failed: return d->failure ? std::string(d->failure->what()) : std::string("failed");
    }
    return {};
}

std::optional<SceneLoadJob::Result> SceneLoadJob::takeResult() {
    std::lock_guard lock(d->mutex);
    std::optional<Result> out = std::move(d->ready);
    d->ready.reset();
    return out;
}

std::optional<Error> SceneLoadJob::error() const {
    std::lock_guard lock(d->mutex);
    return d->failure;
}

bool SceneLoadJob::isFinished() const {
    std::lock_guard lock(d->mutex);
    return d->stage == Stage::Done || d->stage == Stage::Failed;
}

void SceneLoadJob::wait() {
    std::unique_lock lock(d->mutex);
    d->finished.wait(lock, [this] { return d->stage == Stage::Done || d->stage == Stage::Failed; });
}

void SceneLoadJob::cancel() {
    {
        std::lock_guard lock(d->mutex);
        d->cancelled = true;
        d->ready.reset();
    }
    d->released.notify_all();
}

void SceneLoadJob::releaseInference() {
    {
        std::lock_guard lock(d->mutex);
        d->inferenceReleased = true;
    }
    d->released.notify_all();
}

} // namespace mvcl
