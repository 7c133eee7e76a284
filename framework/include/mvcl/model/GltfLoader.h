#pragma once
/// \file GltfLoader.h
/// glTF 2.0 (.gltf / .glb) → Scene, with our own validation on top of tinygltf.

#include <mvcl/core/Export.h>

#include <mvcl/model/LayerRules.h>
#include <mvcl/model/Scene.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace mvcl {

struct GltfLoadOptions {
    /// Rules applied to meshes without `extras.layer`.
    LayerRules layerRules;
    /// Files larger than this are rejected before parsing (bytes).
    std::uint64_t maxFileBytes = 1ull << 30;
    /// Images with more pixels than this are not decoded (decompression bombs): the material's
    /// factor is used, with a warning. 2²⁶ = 8192 × 8192.
    std::uint64_t maxTexturePixels = 1ull << 26;
    /// All decoded images of one file with their mip chains stay below this many bytes.
    std::uint64_t maxTextureBytes = 1ull << 30;
    /// A file whose geometry would need more than this many bytes once loaded (its meshes, one
    /// copy per instance, and the tracer's BVH over them; estimated from the accessors' counts)
    /// is refused before any geometry is read, with the estimate in the error. 0 = no limit.
    std::uint64_t maxGeometryBytes = 0;
};

/// Loads a glTF file. Meshes get their layer from `extras.layer` (node, then mesh), then from
/// the rules; the rest stay LayerSource::Unassigned for SceneLoader's containment inference.
/// Throws mvcl::Error naming the file and the problem for anything invalid.
MVCL_EXPORT Scene loadGltf(const std::filesystem::path &path, const GltfLoadOptions &options = {});

/// Same, from memory (fuzzing, tests). `name` is used in error messages; external resources are
/// resolved relative to `baseDir` and may not leave it.
MVCL_EXPORT Scene loadGltfFromMemory(std::span<const std::uint8_t> bytes, const std::string &name,
                         const std::filesystem::path &baseDir, const GltfLoadOptions &options = {});

} // namespace mvcl
