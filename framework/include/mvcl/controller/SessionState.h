#pragma once
/// \file SessionState.h
/// The editable state of one view as plain values — what one undo step restores and what a
/// test compares: the camera, the visible layers, the renamed layers and the lens stack. The scene itself (source,
/// layer rules) is not in it: changing the scene starts a new history.

#include <mvcl/controller/LensState.h>
#include <mvcl/model/LayerTable.h>
#include <mvcl/view/Camera.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mvcl {

/// A view in compare mode: the stack right of the divider, and where the divider stands.
struct CompareState {
    std::vector<LensState> lenses; ///< bottom → top
    float divider = 0.5f;          ///< normalised x

    bool operator==(const CompareState &other) const = default;
};

struct SessionState {
    Camera camera; ///< scene space
    /// Layers primary rays may hit outside every lens (RayPolicy primary layerMask).
    uint32_t visibleLayers = kAllLayers;
    std::vector<LensState> lenses; ///< bottom → top (left of the divider in compare mode)
    std::optional<CompareState> compare; ///< compare mode: the right-hand side
    /// Layers the user renamed (Controller::setLayerName); the others keep the scene's names.
    std::map<int, std::string> layerNames;

    bool operator==(const SessionState &other) const = default;
};

} // namespace mvcl
