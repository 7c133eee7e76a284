#include <mvcl/model/BuiltinScenes.h>

#include <mvcl/core/Error.h>
#include <mvcl/model/MeshClosure.h>

#include <glm/geometric.hpp>

namespace mvcl {

namespace {

uint32_t addMaterial(Scene &scene, Material material) {
    scene.materials.push_back(std::move(material));
    return uint32_t(scene.materials.size() - 1);
}

Material phong(std::string name, glm::vec3 color, float specular, float shininess) {
    Material m;
    m.name = std::move(name);
    m.diffuse = color;
    m.ambient = color;
    m.specular = specular;
    m.shininess = shininess;
    return m;
}

/// Axis-aligned cube as the paper stores meshes: 8 shared vertices + 12 triangles, wound
/// counter-clockwise seen from outside.
TriangleMesh makeCube(std::string name, glm::vec3 center, float halfSize, uint32_t material,
                      int layer) {
    TriangleMesh mesh;
    mesh.name = std::move(name);
    mesh.material = material;
    mesh.layer = layer;
    mesh.layerSource = LayerSource::Builtin;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? 1.f : -1.f, (i & 2) ? 1.f : -1.f, (i & 4) ? 1.f : -1.f);
        mesh.positions.push_back(center + halfSize * corner);
    }
    mesh.indices = {
        {0, 4, 6}, {0, 6, 2}, // -x
        {1, 3, 7}, {1, 7, 5}, // +x
        {0, 1, 5}, {0, 5, 4}, // -y
        {2, 6, 7}, {2, 7, 3}, // +y
        {0, 2, 3}, {0, 3, 1}, // -z
        {4, 5, 7}, {4, 7, 6}, // +z
    };
    return mesh;
}

/// The paper's test scene: a cube inside a cube on a floor, with a mirror and a glass sphere.
Scene makeCubeInCube() {
    Scene scene;
    scene.name = "builtin:cube-in-cube";
    scene.ambientLight = glm::vec3(0.12f);
    scene.background = glm::vec3(0.05f, 0.07f, 0.12f);

    const uint32_t outer = addMaterial(scene, phong("outer cube", {0.25f, 0.45f, 0.85f}, 0.4f, 40.f));
    const uint32_t inner = addMaterial(scene, phong("inner cube", {0.9f, 0.2f, 0.15f}, 0.5f, 60.f));
    Material floorMaterial = phong("floor", {0.50f, 0.48f, 0.44f}, 0.1f, 10.f);
    floorMaterial.reflectivity = 0.15f;
    const uint32_t floor = addMaterial(scene, floorMaterial);
    Material mirror = phong("mirror", {0.1f, 0.1f, 0.1f}, 0.8f, 200.f);
    mirror.reflectivity = 0.85f;
    const uint32_t mirrorId = addMaterial(scene, mirror);
    Material glass = phong("glass", {0.05f, 0.05f, 0.05f}, 0.9f, 300.f);
    glass.transparency = 0.92f;
    glass.ior = 1.5f;
    const uint32_t glassId = addMaterial(scene, glass);

    scene.layers.ensure(0).name = "outside";
    scene.layers.ensure(1).name = "inner cube";

    scene.meshes.push_back(makeCube("outer cube", {0.f, 1.f, 0.f}, 1.f, outer, 0));
    scene.meshes.push_back(makeCube("inner cube", {0.f, 1.f, 0.f}, 0.45f, inner, 1));
    scene.spheres.push_back({"mirror sphere", {-2.3f, 0.7f, 0.6f}, 0.7f, mirrorId, 0});
    scene.spheres.push_back({"glass sphere", {1.9f, 0.6f, 1.4f}, 0.6f, glassId, 0});
    scene.planes.push_back({"floor", {0.f, 1.f, 0.f}, 0.f, floor, 0});

    Light light;
    light.name = "key";
    light.type = LightType::Point;
    light.position = {5.f, 9.f, 2.5f};
    light.intensity = glm::vec3(1.f);
    scene.lights.push_back(light);

    scene.cameras.push_back({"default", {0.5f, 3.6f, 7.5f}, {0.f, 0.9f, 0.f}, {0.f, 1.f, 0.f}, 40.f});
    return scene;
}

/// Four nested spheres, one layer each, outermost first.
Scene makeOnion() {
    Scene scene;
    scene.name = "builtin:onion";
    scene.ambientLight = glm::vec3(0.12f);
    static const char *kNames[] = {"skin", "flesh", "core", "seed"};
    static const glm::vec3 kColors[] = {
        {0.85f, 0.70f, 0.35f}, {0.90f, 0.90f, 0.75f}, {0.55f, 0.75f, 0.35f}, {0.60f, 0.30f, 0.20f}};
    for (int i = 0; i < 4; ++i) {
        const uint32_t material = addMaterial(scene, phong(kNames[i], kColors[i], 0.3f, 30.f));
        scene.layers.ensure(i).name = kNames[i];
        scene.spheres.push_back({kNames[i], {0.f, 1.f, 0.f}, 1.f - 0.22f * float(i), material, i});
    }
    const uint32_t floor = addMaterial(scene, phong("floor", {0.7f, 0.7f, 0.7f}, 0.f, 1.f));
    scene.planes.push_back({"floor", {0.f, 1.f, 0.f}, 0.f, floor, 0});

    Light light;
    light.name = "sun";
    light.type = LightType::Directional;
    light.direction = glm::normalize(glm::vec3(-0.4f, -1.f, -0.6f));
    light.intensity = glm::vec3(1.f);
    scene.lights.push_back(light);
    scene.cameras.push_back({"default", {0.f, 2.2f, 4.f}, {0.f, 0.9f, 0.f}, {0.f, 1.f, 0.f}, 40.f});
    return scene;
}

} // namespace

std::vector<std::string> builtinSceneNames() { return {"cube-in-cube", "onion"}; }

Scene makeBuiltinScene(std::string_view name) {
    const auto withClosure = [](Scene scene) {
        recordMeshClosure(scene);
        return scene;
    };
    if (name == "cube-in-cube") return withClosure(makeCubeInCube());
    if (name == "onion") return withClosure(makeOnion());
    std::string known;
    for (const std::string &n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
    throw Error("builtin:" + std::string(name), "no such built-in scene (known: " + known + ")");
}

} // namespace mvcl
