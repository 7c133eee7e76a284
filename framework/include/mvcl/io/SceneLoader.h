#pragma once
/// \file SceneLoader.h
/// One entry point for every scene source: "builtin:<name>", .gltf or .glb. Applies layer rules,
/// infers the layers nobody assigned, and gives scenes without lights a default light rig.

#include <mvcl/model/LayerRules.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/LayerInference.h>

#include <string_view>

namespace mvcl {

struct SceneLoadOptions {
    LayerRules layerRules;
    LayerInferenceSettings inference;
};

/// Throws mvcl::Error naming the source and the problem.
Scene loadScene(std::string_view source, const SceneLoadOptions &options = {});

} // namespace mvcl
