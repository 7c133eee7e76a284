#pragma once
/// \file LoadedScene.h
/// A scene and its tracer from one call, with one BVH build: the scene is read with its layer
/// inference left to the caller (LayerInferenceTiming::ByCaller), the tracer is built over it,
/// inference runs on that tracer, and the tracer then takes the inferred layers in a copy of its
/// arrays instead of a second build (Tracer(scene, sameGeometry)).
///
/// An app that wants an image before inference ends (the viewer) does the steps itself:
/// loadScene() with ByCaller, a tracer, the first image, finishLayers() on a copy of the scene,
/// then Tracer(copy, tracer) and a new session.

#include <mvcl/core/Export.h>

#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <memory>
#include <span>
#include <string>

namespace mvcl {

struct MVCL_EXPORT LoadedScene {
    /// On the heap: the tracer keeps a reference to it.
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Tracer> tracer;
    /// Wall time of reading and checking the files (without inference and BVH).
    double readMilliseconds = 0.0;

    /// loadScene(sources, options) and a tracer; options.inferenceTiming is ignored (ByCaller is
    /// how this works). Throws mvcl::Error as loadScene() does.
    static LoadedScene load(std::span<const std::string> sources, const SceneLoadOptions &options = {});
};

} // namespace mvcl
