#pragma once
/// \file LensStackFile.h
/// Lens-stack (session) files: a scene, a camera, layer rules and a stack of lenses with their
/// regions and properties, as JSON — and the command line's one-lens form "type:key=value,...".
///
///     { "version": 1,
///       "scene": "builtin:cube-in-cube",
///       "camera": {"eye": [x,y,z], "target": [x,y,z], "up": [0,1,0], "fov": 40}  or  {"name": "cam"},
///       "layerRules": [{"match": "*Skin*", "layer": 0}],
///       "visibleLayers": "0,2-",
///       "lenses": [{"type": "layer", "label": "reveal", "enabled": true,
///                   "region": {"shape": "ellipse", "center": [0.5,0.5], "size": [0.4,0.4],
///                              "feather": 6, "outline": 2, "outlineColor": [1,1,1]},
///                   "properties": {"layers": "1-", "distance": 0}}] }      // bottom → top
///
/// A relative scene path is relative to the file's folder. Every key is optional except a
/// lens's "type". "visibleLayers" (layer-set text, default "all") is the layers primary rays
/// see outside every lens; it is written only when some layer is hidden, so files of views
/// that hide nothing read the same in builds that predate it. Unknown keys anywhere are an error naming the
/// file and the JSON path; property values are read with the property's own declaration.

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensStack.h>
#include <mvcl/model/LayerContact.h>
#include <mvcl/model/LayerRules.h>
#include <mvcl/model/LayerTable.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace mvcl {

class LensRegistry;

/// The view a lens-stack file asks for: one of the scene's own cameras, or an explicit look-at.
struct LensStackCamera {
    /// A camera of the scene by name or index ("0"); when set, the fields below are unused.
    std::string sceneCamera;
    glm::vec3 eye{0.f, 0.f, 5.f}; ///< world space (the file's units)
    glm::vec3 target{0.f};
    glm::vec3 up{0.f, 1.f, 0.f};
    float verticalFovDegrees = 40.f;

    bool operator==(const LensStackCamera &other) const = default;
};

struct LensStackDescription {
    std::string scene; ///< model path or builtin:NAME; empty = none given
    /// Further model files layered inside `scene` ("scene": ["skin.stl", "bone.stl"]), in order.
    std::vector<std::string> moreScenes;
    std::optional<LensStackCamera> camera;
    LayerRules layerRules;
    /// Layers primary rays may hit outside every lens (the base policy's primary layer mask).
    uint32_t visibleLayers = kAllLayers;
    /// The scene's contact tolerance for touching layers ("layerContact": {"relative": f} or
    /// {"sceneUnits": d}); off when the file has none.
    LayerContact layerContact;
    /// The memory budget of the scene's model ("memoryBudgetMiB": whole MiB ≥ 1; bytes here,
    /// 0 = none given: SceneLoadOptions::memoryBudgetBytes's default).
    std::uint64_t memoryBudgetBytes = 0;
    /// Layers the user renamed ("layerNames": {"2": "bone"}), over every other source of names.
    std::map<int, std::string> layerNames;
    LensStack lenses; ///< every lens committed
};

/// Equal scene, camera, rules, visible layers and lenses (type, label, committed enabled/region/properties).
MVCL_EXPORT bool operator==(const LensStackDescription &a, const LensStackDescription &b);

/// Reads and commits a lens-stack file; a relative scene path comes back resolved against the
/// file's folder. A session file of several views (version 2, SessionFile.h) reads as its first
/// view. Throws mvcl::Error(path, "json.path: problem").
MVCL_EXPORT LensStackDescription readLensStackFile(const std::filesystem::path &path,
                                       const LensRegistry &registry);
/// The same from text; errors name `sourceName` in place of a file.
MVCL_EXPORT LensStackDescription parseLensStackJson(std::string_view text, const std::string &sourceName,
                                        const LensRegistry &registry);

/// The file's text: every lens with its committed state, property values in canonical text.
MVCL_EXPORT std::string lensStackJson(const LensStackDescription &description);
/// Writes a scene file path relative to the file's folder, and writes atomically (a temporary
/// file in the same folder, then rename), so a failed write
/// leaves an existing file as it was. Throws mvcl::Error(path, problem).
MVCL_EXPORT void writeLensStackFile(const std::filesystem::path &path, const LensStackDescription &description);

/// One lens from the command line: "type:key=value,key=value" where a key is a property of the
/// lens or a region key (shape, center, size, points, feather, outline, outlineColor) or label,
/// enabled. Values with commas are bracketed ("center=[0.3,0.5]", "layers=[1,2]"). Returns the
/// lens committed; throws mvcl::Error("--lens", problem naming the spec and the key).
MVCL_EXPORT std::shared_ptr<Lens> parseLensSpec(std::string_view spec, const LensRegistry &registry);

} // namespace mvcl
