#include <mvcl/io/LoadedScene.h>

#include <chrono>

namespace mvcl {

namespace {
double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
} // namespace

LoadedScene LoadedScene::load(std::span<const std::string> sources, const SceneLoadOptions &options) {
    SceneLoadOptions byCaller = options;
    byCaller.inferenceTiming = LayerInferenceTiming::ByCaller;
    LoadedScene loaded;
    auto start = std::chrono::steady_clock::now();
    loaded.scene = std::make_unique<Scene>(loadScene(sources, byCaller));
    loaded.readMilliseconds = millisecondsSince(start);
    loaded.tracer = std::make_unique<Tracer>(*loaded.scene);
    // Nothing else queries the tracer yet, so inference may change the scene it was built over.
    if (finishLayers(*loaded.scene, *loaded.tracer, options))
        loaded.tracer = std::make_unique<Tracer>(*loaded.scene, *loaded.tracer);
    return loaded;
}

} // namespace mvcl
