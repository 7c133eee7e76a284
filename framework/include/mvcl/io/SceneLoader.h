#pragma once
/// \file SceneLoader.h
/// One entry point for every scene source: "builtin:<name>", .gltf or .glb. Applies layer rules,
/// infers the layers nobody assigned, and gives model files without lights a default light rig
/// (unless told not to), and sets the scene's layer contact tolerance.

#include <mvcl/core/Export.h>

#include <mvcl/model/LayerContact.h>
#include <mvcl/model/LayerRules.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/LayerInference.h>

#include <cstdint>
#include <string_view>

namespace mvcl {

/// Whether a model file without lights gets the default key and fill lights.
enum class DefaultLights : uint8_t {
    WhenTheFileHasNone, ///< the inspection rig, so that every surface reads
    Never,              ///< keep the file's lights as they are, none included (ambient only)
};

struct SceneLoadOptions {
    LayerRules layerRules;
    LayerInferenceSettings inference;
    DefaultLights defaultLights = DefaultLights::WhenTheFileHasNone;
    /// Becomes Scene::layerContact when enabled (model files carry none of their own).
    LayerContact layerContact;
    /// A model whose geometry would need more memory than this (bytes; meshes and BVH, estimated
    /// before loading: GltfLoadOptions::maxGeometryBytes) is refused with the estimate.
    /// 0 = defaultMemoryBudgetBytes().
    std::uint64_t memoryBudgetBytes = 0;
};

/// Half the machine's physical memory: what a model may take when nobody says otherwise.
MVCL_EXPORT std::uint64_t defaultMemoryBudgetBytes();

/// Throws mvcl::Error naming the source and the problem.
MVCL_EXPORT Scene loadScene(std::string_view source, const SceneLoadOptions &options = {});

} // namespace mvcl
