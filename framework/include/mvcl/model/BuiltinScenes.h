#pragma once
/// \file BuiltinScenes.h
/// Procedural scenes, addressed as "builtin:<name>".

#include <mvcl/core/Export.h>

#include <mvcl/model/Scene.h>

#include <string>
#include <string_view>
#include <vector>

namespace mvcl {

/// Names accepted by makeBuiltinScene(), the default ("cube-in-cube") first.
MVCL_EXPORT std::vector<std::string> builtinSceneNames();

/// Builds a built-in scene. Throws mvcl::Error naming the known scenes if `name` is unknown.
///  - "cube-in-cube": the paper's scene: an outer cube (layer 0) around an inner cube (layer 1),
///    a floor plane, a reflecting sphere, a refracting sphere and one point light.
///  - "onion": four nested spheres, layers 0..3.
MVCL_EXPORT Scene makeBuiltinScene(std::string_view name);

} // namespace mvcl
