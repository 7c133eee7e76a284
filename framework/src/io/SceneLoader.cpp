#include <mvcl/io/SceneLoader.h>

#include "ModelFormat_p.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/MeshClosure.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <unistd.h>

namespace mvcl {

namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";

/// Files rarely bring lights that suit an inspection view: a key light from the upper front
/// and a weaker fill from the other side, plus ambient, so every surface reads.
void addDefaultLights(Scene &scene) {
    Light key;
    key.name = "default key";
    key.type = LightType::Directional;
    key.direction = glm::normalize(glm::vec3(-0.5f, -1.f, -0.7f));
    key.intensity = glm::vec3(0.85f);
    Light fill = key;
    fill.name = "default fill";
    fill.direction = glm::normalize(glm::vec3(0.7f, -0.3f, 0.4f));
    fill.intensity = glm::vec3(0.3f);
    scene.lights.push_back(key);
    scene.lights.push_back(fill);
    scene.ambientLight = glm::vec3(0.15f);
    scene.report.warnings.push_back("the file has no lights: using the default key and fill lights");
}

/// The reader for a file: its content when that is recognisable (a warning says when it
/// disagrees with the extension), else its extension; a file that is clearly something else
/// (an image, an archive) or empty fails here with one line.
detail::ModelFormat chooseFormat(const std::filesystem::path &path, const std::string &name, LoadReport &report) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error(name, "cannot read the file (" + ec.message() + ")");
    if (size == 0) throw Error(name, "the file is empty");
    std::vector<std::uint8_t> head(std::min<std::uintmax_t>(size, 1024));
    std::ifstream file(path, std::ios::binary);
    if (!file.read(reinterpret_cast<char *>(head.data()), std::streamsize(head.size())))
        throw Error(name, "cannot read the file");
    const std::optional<detail::ModelFormat> byExtension = detail::modelFormatFromExtension(path.extension().string());
    const std::optional<detail::ModelFormat> byContent = detail::modelFormatFromContent(head, size);
    if (byContent && byExtension && *byContent != *byExtension)
        report.warnings.push_back(std::string("the file is named ") + path.extension().string() + " but holds " +
                                  detail::modelFormatName(*byContent) + "; read as " +
                                  detail::modelFormatName(*byContent));
    if (byContent) return *byContent;
    if (const std::string other = detail::otherFileKind(head); !other.empty())
        throw Error(name, "the file is " + other + ", not a model");
    if (byExtension) return *byExtension;
    throw Error(name, "unknown scene type (expected .gltf, .glb, .obj, .stl, .ply or builtin:<name>)");
}

/// One file or built-in scene as its reader gives it: no inference, lights or names yet.
Scene readSource(std::string_view source, const SceneLoadOptions &options) {
    if (source.starts_with(kBuiltinPrefix)) return makeBuiltinScene(source.substr(kBuiltinPrefix.size()));
    const std::filesystem::path path(source);
    const std::string name(source);
    LoadReport notes;
    const detail::ModelFormat format = chooseFormat(path, name, notes);
    Scene scene;
    if (format == detail::ModelFormat::Gltf) {
        GltfLoadOptions gltfOptions;
        gltfOptions.layerRules = options.layerRules;
        gltfOptions.maxGeometryBytes = options.memoryBudgetBytes ? options.memoryBudgetBytes : defaultMemoryBudgetBytes();
        scene = loadGltf(path, gltfOptions);
    } else {
        MeshFileOptions meshOptions;
        meshOptions.layerRules = options.layerRules;
        meshOptions.upAxis = options.upAxis;
        meshOptions.unit = options.unit;
        const MeshFormat meshFormat = format == detail::ModelFormat::Obj   ? MeshFormat::Obj
                                      : format == detail::ModelFormat::Stl ? MeshFormat::Stl
                                                                           : MeshFormat::Ply;
        scene = loadMeshFile(path, meshFormat, meshOptions);
    }
    scene.report.warnings.insert(scene.report.warnings.begin(), notes.warnings.begin(), notes.warnings.end());
    return scene;
}

/// The longest common prefix of the names, cut back to the last separator so that
/// "VH_F_renal_pyramid_L_a" and "VH_F_renal_pyramid_L_b" give "VH_F_renal_pyramid_L".
std::string commonPrefix(const std::vector<std::string_view> &names) {
    if (names.empty()) return {};
    std::string_view prefix = names.front();
    for (std::string_view n : names) {
        std::size_t i = 0;
        while (i < prefix.size() && i < n.size() && prefix[i] == n[i]) ++i;
        prefix = prefix.substr(0, i);
    }
    const bool whole = std::all_of(names.begin(), names.end(), [&](std::string_view n) { return n.size() == prefix.size(); });
    if (!whole) {
        const std::size_t cut = prefix.find_last_of("_-. ");
        prefix = cut == std::string_view::npos ? std::string_view() : prefix.substr(0, cut);
    }
    while (!prefix.empty() && std::string_view("_-. ").find(prefix.back()) != std::string_view::npos) prefix.remove_suffix(1);
    return std::string(prefix);
}

std::string_view meshName(const TriangleMesh &m) { return m.nodeName.empty() ? m.meshName : m.nodeName; }

/// Layers still named "layer N" take the common prefix of their meshes' names (glTF node names,
/// OBJ groups, STL solids, a file's stem) when there is one. A prefix every mesh of the scene
/// shares ("VH_F" in an atlas) tells layers apart no better than their numbers, so it names a
/// layer only when that layer holds every mesh.
void nameLayersByMeshNames(Scene &scene) {
    std::vector<std::string_view> all;
    for (const TriangleMesh &m : scene.meshes) all.push_back(meshName(m));
    const std::string sceneWide = commonPrefix(all);
    for (const Layer &layer : std::vector<Layer>(scene.layers.layers())) {
        if (layer.name != "layer " + std::to_string(layer.id)) continue;
        std::vector<std::string_view> names;
        for (const TriangleMesh &m : scene.meshes)
            if (m.layer == layer.id) names.push_back(meshName(m));
        if (names.empty() || std::any_of(names.begin(), names.end(), [](std::string_view n) { return n.empty(); })) continue;
        const std::string prefix = commonPrefix(names);
        const bool telling = names.size() == all.size() || prefix.size() > sceneWide.size();
        if (prefix.size() >= 2 && telling) scene.layers.ensure(layer.id).name = prefix;
    }
}

/// Scene space of several files → one: each file's scene space is its own world minus its
/// origin; the merged origin is the centre of the union of their world bounds (in double).
Scene mergeScenes(std::vector<Scene> parts, std::span<const std::string> sources) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const Scene &s : parts) {
        const Bounds3f b = s.bounds();
        lo = glm::min(lo, s.worldOrigin + glm::dvec3(b.min));
        hi = glm::max(hi, s.worldOrigin + glm::dvec3(b.max));
    }
    Scene merged;
    merged.name = describeSources(sources);
    merged.worldOrigin = 0.5 * (lo + hi);
    for (std::size_t i = 0; i < parts.size(); ++i) {
        Scene &s = parts[i];
        const glm::dvec3 shift = s.worldOrigin - merged.worldOrigin;
        const auto move = [&shift](glm::vec3 p) { return glm::vec3(glm::dvec3(p) + shift); };
        const auto materialBase = uint32_t(merged.materials.size());
        const int textureBase = int(merged.textures.size());
        for (Material m : s.materials) {
            for (TextureRef *t : {&m.metallicRoughness.baseColorTexture, &m.metallicRoughness.metallicRoughnessTexture,
                                  &m.metallicRoughness.normalTexture, &m.metallicRoughness.occlusionTexture,
                                  &m.metallicRoughness.emissiveTexture})
                if (t->isSet()) t->texture += textureBase;
            merged.materials.push_back(std::move(m));
        }
        for (Texture &t : s.textures) merged.textures.push_back(std::move(t));
        const std::string stem = std::filesystem::path(sources[i]).stem().string();
        merged.layers.ensure(int(i)).name = stem;
        for (TriangleMesh &m : s.meshes) {
            for (glm::vec3 &p : m.positions) p = move(p);
            m.material += materialBase;
            if (m.layerSource != LayerSource::Rule) {
                m.layer = int(i);
                m.layerSource = LayerSource::File;
            }
            merged.meshes.push_back(std::move(m));
        }
        for (Light l : s.lights) {
            l.position = move(l.position);
            merged.lights.push_back(l);
        }
        for (CameraDesc c : s.cameras) {
            c.eye = move(c.eye);
            c.target = move(c.target);
            merged.cameras.push_back(c);
        }
        for (const std::string &w : s.report.warnings) merged.report.warnings.push_back(stem + ": " + w);
        for (const std::string &a : s.report.assumptions)
            if (std::find(merged.report.assumptions.begin(), merged.report.assumptions.end(), a) == merged.report.assumptions.end())
                merged.report.assumptions.push_back(a);
        merged.report.degenerateTrianglesDropped += s.report.degenerateTrianglesDropped;
        merged.report.nonUnitNormalsFixed += s.report.nonUnitNormalsFixed;
        merged.report.primitivesSkipped += s.report.primitivesSkipped;
        merged.report.texturesDecoded += s.report.texturesDecoded;
        merged.report.textureBytes += s.report.textureBytes;
    }
    for (const TriangleMesh &m : merged.meshes) merged.layers.ensure(m.layer);
    return merged;
}

bool anyUnassigned(const Scene &scene) {
    return std::any_of(scene.meshes.begin(), scene.meshes.end(),
                       [](const TriangleMesh &m) { return m.layerSource == LayerSource::Unassigned; });
}

/// Every layer a mesh, sphere or plane is on has an entry in the layer table.
void ensureLayers(Scene &scene) {
    for (const TriangleMesh &m : scene.meshes) scene.layers.ensure(m.layer);
    for (const Sphere &s : scene.spheres) scene.layers.ensure(s.layer);
    for (const Plane &p : scene.planes) scene.layers.ensure(p.layer);
}

/// Names from the meshes' names (model files), then from the rules (which win).
void nameLayers(Scene &scene, bool isModelFile, const SceneLoadOptions &options) {
    if (isModelFile) nameLayersByMeshNames(scene);
    options.layerRules.nameLayers(scene.layers);
}

/// What every scene gets once read: lights, inference, contact tolerance, layer table and names.
Scene finish(Scene scene, bool isModelFile, const SceneLoadOptions &options) {
    if (isModelFile && scene.lights.empty() && options.defaultLights == DefaultLights::WhenTheFileHasNone)
        addDefaultLights(scene);
    const bool inferNow = options.inferenceTiming == LayerInferenceTiming::WhileLoading;
    if (inferNow && anyUnassigned(scene)) {
        const auto start = std::chrono::steady_clock::now();
        inferLayersByContainment(scene, options.inference);
        scene.report.inferenceMilliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    if (options.layerContact.isEnabled()) scene.layerContact = options.layerContact;
    ensureLayers(scene);
    if (inferNow) nameLayers(scene, isModelFile, options);
    if (scene.materials.empty()) {
        Material fallback;
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }
    return scene;
}

} // namespace

std::uint64_t defaultMemoryBudgetBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return 4ull << 30; // unknown: a budget any machine mvcl runs on has
    return std::uint64_t(pages) * std::uint64_t(pageSize) / 2;
}

Scene loadScene(std::string_view source, const SceneLoadOptions &options) {
    return finish(readSource(source, options), !source.starts_with(kBuiltinPrefix), options);
}

Scene loadScene(std::span<const std::string> sources, const SceneLoadOptions &options) {
    if (sources.empty()) throw Error("", "no scene given");
    if (sources.size() == 1) return loadScene(sources.front(), options);
    if (sources.size() > std::size_t(kMaxLayers))
        throw Error(describeSources(sources), std::to_string(sources.size()) + " files, more than the " +
                                                  std::to_string(kMaxLayers) + " layers a scene has");
    std::vector<Scene> parts;
    for (const std::string &source : sources) {
        if (std::string_view(source).starts_with(kBuiltinPrefix))
            throw Error(source, "a built-in scene cannot be combined with other files");
        parts.push_back(readSource(source, options));
    }
    Scene merged = mergeScenes(std::move(parts), sources);
    recordMeshClosure(merged);
    return finish(std::move(merged), true, options);
}

bool finishLayers(Scene &scene, const Tracer &tracer, const SceneLoadOptions &options) {
    std::vector<int> before;
    for (const TriangleMesh &m : scene.meshes) before.push_back(m.layer);
    if (anyUnassigned(scene)) {
        const auto start = std::chrono::steady_clock::now();
        inferLayersByContainment(scene, tracer, options.inference);
        scene.report.inferenceMilliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    ensureLayers(scene);
    nameLayers(scene, !scene.name.starts_with(kBuiltinPrefix), options);
    for (std::size_t i = 0; i < scene.meshes.size(); ++i)
        if (scene.meshes[i].layer != before[i]) return true;
    return false;
}

std::string describeSources(std::span<const std::string> sources) {
    std::string text;
    for (const std::string &s : sources) text += (text.empty() ? "" : " + ") + s;
    return text;
}

} // namespace mvcl
