#pragma once
/// \file SceneLoadJob.h
/// Opening a scene without blocking the caller: a thread of the job's own reads the files and
/// builds the tracer, hands over the scene as read as soon as it can be rendered, then infers
/// the layers on that same tracer and hands over the inferred scene with its tracer (the BVH
/// copied onto the new layers, not built again). An app shows the first result at once, keeps
/// drawing meanwhile, and swaps in the second when it comes.
///
/// A scene with nothing to infer (every mesh placed by a rule, a file or a built-in scene) gives
/// one result only, already final. Results are shared: the session that renders one keeps it
/// alive, and the job keeps the first while it infers on its tracer.
///
/// A large scene (kQuickBvhFromTriangles and more) is first handed out on a quick BVH
/// (BvhQuality::Quick: a fraction of the full build's time, slower queries, the same answers);
/// the full build follows once the first image is out, and the next result carries it (with the
/// inferred layers, or alone when there is nothing to infer).

#include <mvcl/core/Error.h>
#include <mvcl/core/Export.h>
#include <mvcl/io/SceneLoader.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mvcl {

struct Scene;
class Tracer;

class MVCL_EXPORT SceneLoadJob {
public:
    enum class Stage {
        Reading,         ///< reading and checking the files
        BuildingBvh,     ///< building the tracer of the scene as read
        RefiningBvh,     ///< the first result is out on a quick BVH; building the full one
        InferringLayers, ///< the first result is out; inferring the layers on the full BVH
        Done,            ///< the final result is out (or was cancelled)
        Failed,          ///< error() says why; no further result comes
    };

    struct Result {
        std::shared_ptr<const Scene> scene;
        std::shared_ptr<const Tracer> tracer; ///< built over *scene
        /// False for the scene as read when its layers are still to be inferred (its meshes
        /// wait on layer 0, its layers unnamed); true once they are final (the last result, and
        /// a first result on a quick BVH when there is nothing to infer). The tracer's
        /// buildStats().bvhQuality says which BVH a result carries.
        bool layersAreFinal = false;
    };

    /// When the job infers the layers, once the scene as read is handed out.
    enum class InferenceStart {
        AtOnce,
        /// After releaseInference() (or cancel()): an app that shows the first result lets its
        /// first image render on every core before inference takes them.
        WhenReleased,
    };

    /// Which BVH the first result carries.
    enum class FirstBvh {
        /// Quick for scenes of kQuickBvhFromTriangles and more (their full build takes long
        /// enough to hold up a first image), full below.
        QuickWhenLarge,
        Quick,
        Full, ///< one build, the full one
    };
    /// Below this, a full build takes about a tenth of a second on two cores.
    static constexpr std::size_t kQuickBvhFromTriangles = 262144;

    /// Starts loading at once: loadScene(sources, options) with the inference left to the job
    /// (options.inferenceTiming is ignored).
    SceneLoadJob(std::vector<std::string> sources, SceneLoadOptions options,
                 InferenceStart inferenceStart = InferenceStart::AtOnce, FirstBvh firstBvh = FirstBvh::QuickWhenLarge);
    /// Cancels and waits for the thread.
    ~SceneLoadJob();
    SceneLoadJob(const SceneLoadJob &) = delete;
    SceneLoadJob &operator=(const SceneLoadJob &) = delete;

    Stage stage() const;
    /// A line for a progress display: "reading body.glb", "building the BVH of 394551
    /// triangles", "building the full BVH", "inferring layers", "done", or the error.
    std::string progressText() const;
    /// The newest result not yet taken, once: the first (layers not final) and then the last.
    /// When the last is ready before the first was taken, only the last is handed out.
    std::optional<Result> takeResult();
    /// The error of a failed load (Stage::Failed), naming the file and the problem.
    std::optional<Error> error() const;
    /// Done or Failed: no further result will come.
    bool isFinished() const;
    /// Waits until the job is finished (tests, headless apps).
    void wait();
    /// Stops after the step in progress; no further result is handed out.
    void cancel();
    /// Lets a job made with InferenceStart::WhenReleased go on after its first result: the full
    /// build when the first was quick, the layers' inference (any time; once is enough).
    void releaseInference();

private:
    struct Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
