#pragma once
/// \file SceneLoader.h
/// One entry point for every scene source: "builtin:<name>" or a model file (.gltf, .glb, .obj,
/// .stl, .ply; the content decides when it disagrees with the extension), or several model files
/// as the layers of one scene. Applies layer rules, infers the layers nobody assigned, names the
/// layers, gives model files without lights a default light rig (unless told not to), and sets
/// the scene's layer contact tolerance.

#include <mvcl/core/Export.h>

#include <mvcl/model/LayerContact.h>
#include <mvcl/model/LayerRules.h>
#include <mvcl/model/MeshFileLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/LayerInference.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mvcl {

/// Whether a model file without lights gets the default key and fill lights.
enum class DefaultLights : uint8_t {
    WhenTheFileHasNone, ///< the inspection rig, so that every surface reads
    Never,              ///< keep the file's lights as they are, none included (ambient only)
};

/// Who infers the layers of the meshes that no rule or file placed.
enum class LayerInferenceTiming : uint8_t {
    /// loadScene() does, with a BVH of its own: a second one is built for rendering.
    WhileLoading,
    /// loadScene() leaves them on layer 0 and the layers unnamed; the caller builds the scene's
    /// tracer, calls finishLayers() with it and then moves the tracer onto the result
    /// (Tracer(scene, tracer)): one BVH build per load, and an image can be shown before
    /// inference ends (LoadedScene does all of it).
    ByCaller,
};

struct SceneLoadOptions {
    LayerRules layerRules;
    LayerInferenceSettings inference;
    LayerInferenceTiming inferenceTiming = LayerInferenceTiming::WhileLoading;
    DefaultLights defaultLights = DefaultLights::WhenTheFileHasNone;
    /// Becomes Scene::layerContact when enabled (model files carry none of their own).
    LayerContact layerContact;
    /// Up axis and unit of files that do not say (OBJ, STL, PLY); unset = y and metres, which
    /// Scene::report.assumptions then records.
    std::optional<UpAxis> upAxis;
    std::optional<LengthUnit> unit;
    /// A model whose geometry would need more memory than this (bytes; meshes and BVH, estimated
    /// before loading: GltfLoadOptions::maxGeometryBytes) is refused with the estimate.
    /// 0 = defaultMemoryBudgetBytes().
    std::uint64_t memoryBudgetBytes = 0;
};

/// Half the machine's physical memory: what a model may take when nobody says otherwise.
MVCL_EXPORT std::uint64_t defaultMemoryBudgetBytes();

/// Throws mvcl::Error naming the source and the problem.
MVCL_EXPORT Scene loadScene(std::string_view source, const SceneLoadOptions &options = {});

/// Several model files as one scene: file i's meshes go to layer i (the first file is the
/// outermost) unless a layer rule places them, and layer i is named after file i's stem unless a
/// rule names it. The files are placed in one world (their own coordinates, re-centred once).
/// One source is the same as loadScene(source). Built-in scenes cannot be combined with files.
MVCL_EXPORT Scene loadScene(std::span<const std::string> sources, const SceneLoadOptions &options = {});

/// The second half of a load with LayerInferenceTiming::ByCaller: infers the layers of the
/// meshes still unassigned with `tracer`, built over `scene` as loadScene() returned it (or over
/// a copy that other threads keep querying), and names the layers. Returns whether a mesh moved
/// to another layer: then `tracer` no longer matches and the scene needs Tracer(scene, tracer).
MVCL_EXPORT bool finishLayers(Scene &scene, const Tracer &tracer, const SceneLoadOptions &options);

/// The sources of a scene as text: the path itself for one, "a.stl + b.stl" for several.
MVCL_EXPORT std::string describeSources(std::span<const std::string> sources);

} // namespace mvcl
