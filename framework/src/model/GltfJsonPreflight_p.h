#pragma once
/// \file GltfJsonPreflight_p.h
/// Private to the glTF loader: reads the JSON with nlohmann before tinygltf does, to
///   - name an unsupported required extension (Draco, meshopt, ...) even where tinygltf would
///     fail first with a confusing message;
///   - repair what the glTF-Validator accepts but tinygltf refuses: a `minVersion` above a 2.0
///     `version`, data URIs that are not base64 (RFC 2397 percent-encoding) or have another
///     media type, a `.gltf` buffer without `uri` that nothing reads; wrong JSON types in
///     material texture references and names (warned, not silently dropped);
///   - if tinygltf still refuses the file, drop the parts mvcl does not render (animations,
///     skins, cameras, textures/images/samplers, materials), one group at a time, so that one
///     broken camera does not throw away the model. Each repair adds a warning.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mvcl::gltf {

class GltfJsonPreflight {
public:
    /// `json` is the .gltf text or a GLB's JSON chunk; `isGlb` says which (a GLB's first buffer
    /// may omit its uri). Throws mvcl::Error(source, …) for an unsupported required extension.
    GltfJsonPreflight(std::span<const std::uint8_t> json, bool isGlb, const std::string &source);

    /// The JSON to give tinygltf first, when the repairs changed something.
    const std::optional<std::string> &repaired() const { return m_repaired; }
    /// Warnings for the repairs.
    const std::vector<std::string> &warnings() const { return m_warnings; }

    /// The next, more stripped-down JSON to try after tinygltf refused the previous one, with
    /// the warning naming what was dropped; nullopt when nothing is left to drop.
    std::optional<std::pair<std::string, std::string>> nextFallback();

private:
    void checkRequiredExtensions(const std::string &source) const;
    void repairVersion();
    void repairDataUris();
    void repairBuffersWithoutUri(const std::string &source);
    /// Wrong JSON types in material and texture references (tinygltf drops them silently).
    void repairMaterialTypes();
    void repairNames();

    nlohmann::json m_doc;
    bool m_parsed = false;
    bool m_isGlb = false;
    std::string m_source;
    int m_fallbackStage = 0;
    std::optional<std::string> m_repaired;
    std::vector<std::string> m_warnings;
};

} // namespace mvcl::gltf
