#include <mvcl/io/SceneLoader.h>

#include <mvcl/core/Error.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/GltfLoader.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <filesystem>
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

} // namespace

std::uint64_t defaultMemoryBudgetBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return 4ull << 30; // unknown: a budget any machine mvcl runs on has
    return std::uint64_t(pages) * std::uint64_t(pageSize) / 2;
}

Scene loadScene(std::string_view source, const SceneLoadOptions &options) {
    Scene scene;
    if (source.starts_with(kBuiltinPrefix)) {
        scene = makeBuiltinScene(source.substr(kBuiltinPrefix.size()));
    } else {
        const std::filesystem::path path(source);
        std::string ext = path.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (ext != ".gltf" && ext != ".glb")
            throw Error(std::string(source), "unknown scene type (expected .gltf, .glb or builtin:<name>)");
        GltfLoadOptions gltfOptions;
        gltfOptions.layerRules = options.layerRules;
        gltfOptions.maxGeometryBytes = options.memoryBudgetBytes ? options.memoryBudgetBytes : defaultMemoryBudgetBytes();
        scene = loadGltf(path, gltfOptions);
        if (scene.lights.empty() && options.defaultLights == DefaultLights::WhenTheFileHasNone)
            addDefaultLights(scene);
    }
    const bool anyUnassigned = std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const TriangleMesh &m) {
        return m.layerSource == LayerSource::Unassigned;
    });
    if (anyUnassigned) inferLayersByContainment(scene, options.inference);
    if (options.layerContact.isEnabled()) scene.layerContact = options.layerContact;
    for (const TriangleMesh &m : scene.meshes) scene.layers.ensure(m.layer);
    for (const Sphere &s : scene.spheres) scene.layers.ensure(s.layer);
    for (const Plane &p : scene.planes) scene.layers.ensure(p.layer);
    if (scene.materials.empty()) {
        Material fallback;
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }
    return scene;
}

} // namespace mvcl
