// glTF materials: the metallic-roughness → Phong/Whitted mapping (bright metals, never black),
// emission, alpha modes, double-sidedness, and a metallic × roughness grid as a golden image
// rendered through mvcl-render (regenerate with MVCL_UPDATE_GOLDEN=1 and look at it).

#include "GltfTestWriter.h"
#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/PhongTerms.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace mvcl;
using namespace mvcl::test;
namespace fs = std::filesystem;

namespace {

/// A 2×2 square at z = 0 facing +Z, with TEXCOORD_0 (0,0) top left … (1,1) bottom right.
GltfWriter squareFile(nlohmann::json material) {
    GltfWriter w;
    const int pos = w.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
    const std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    const int tex = w.accessor(w.view(uv), 5126, 4, "VEC2");
    const int idx = w.indices16({0, 1, 2, 0, 2, 3});
    w.doc["materials"].push_back(material);
    const int m = w.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}}, {"indices", idx}, {"material", 0}});
    w.scene({w.node({{"mesh", m}})});
    return w;
}

/// Radiance straight down −Z at (x, y) onto the loaded scene with a light from the camera side.
glm::vec3 shadeAt(Scene &scene, float x, float y, bool addLight = true) {
    if (addLight) {
        Light l;
        l.type = LightType::Directional;
        l.direction = glm::normalize(glm::vec3(0.2f, 0.1f, -1.f));
        l.intensity = glm::vec3(1.f);
        scene.lights.push_back(l);
    }
    scene.ambientLight = glm::vec3(0.1f);
    scene.background = glm::vec3(0.f);
    const Tracer tracer(scene);
    RayCounters counters;
    return WhittedIntegrator(tracer).radiance({{x, y, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
}

float luminance(const glm::vec3 &c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

} // namespace

TEST(GltfMaterials, EmptyMetallicRoughnessIsARoughWhiteMetalThatIsNotBlack) {
    // glTF's defaults: base colour 1, metallic 1, roughness 1.
    Scene scene = squareFile({{"pbrMetallicRoughness", nlohmann::json::object()}}).load();
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material &m = scene.materials[0];
    EXPECT_TRUE(m.hasMetallicRoughness);
    EXPECT_EQ(m.diffuse, glm::vec3(0.f));
    EXPECT_FLOAT_EQ(m.specular, 1.f);
    EXPECT_FLOAT_EQ(m.shininess, 1.f);
    EXPECT_EQ(m.ambient, glm::vec3(1.f));
    const glm::vec3 c = shadeAt(scene, 0.f, 0.f);
    EXPECT_GT(luminance(c), 0.5f) << c.x << " " << c.y << " " << c.z;
}

TEST(GltfMaterials, MetalsTintHighlightsAndReflections) {
    Scene scene = squareFile({{"pbrMetallicRoughness",
                               {{"baseColorFactor", {1.0, 0.5, 0.1, 1.0}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}})
                      .load();
    const Material &m = scene.materials[0];
    EXPECT_EQ(m.specularColor, glm::vec3(1.f, 0.5f, 0.1f));
    EXPECT_FLOAT_EQ(m.reflectivity, 1.f);
    EXPECT_EQ(m.diffuse, glm::vec3(0.f));
    // A mirror of a white background is the base colour.
    scene.background = glm::vec3(1.f);
    const Tracer tracer(scene);
    RayCounters counters;
    const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
    EXPECT_NEAR(c.x, 1.f + m.ambient.x * scene.ambientLight.x, 1e-4f);
    EXPECT_NEAR(c.y / c.x, 0.5f, 0.05f);
}

TEST(GltfMaterials, DielectricsKeepAFresnelFloorAndStayDiffuse) {
    const PhongTerms rough = phongFromMetallicRoughness(glm::vec3(0.f), 0.f, 1.f);
    EXPECT_FLOAT_EQ(rough.specular, 0.04f); // a black rough plastic still shows the light
    const PhongTerms smooth = phongFromMetallicRoughness(glm::vec3(0.2f, 0.4f, 0.6f), 0.f, 0.f);
    EXPECT_FLOAT_EQ(smooth.specular, 0.3f);
    EXPECT_EQ(smooth.diffuse, glm::vec3(0.2f, 0.4f, 0.6f));
    EXPECT_EQ(smooth.specularColor, glm::vec3(1.f));
    EXPECT_FLOAT_EQ(smooth.reflectivity, 0.f);
    // Roughness widens the highlight.
    EXPECT_GT(phongFromMetallicRoughness(glm::vec3(1.f), 0.f, 0.2f).shininess,
              phongFromMetallicRoughness(glm::vec3(1.f), 0.f, 0.6f).shininess);
}

TEST(GltfMaterials, EmissionWithStrengthGlowsWithoutLights) {
    Scene scene = squareFile({{"emissiveFactor", {1.0, 0.5, 0.25}},
                              {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}})
                      .load();
    EXPECT_EQ(scene.materials[0].emission, glm::vec3(4.f, 2.f, 1.f));
    scene.ambientLight = glm::vec3(0.f);
    const glm::vec3 c = shadeAt(scene, 0.f, 0.f, false);
    EXPECT_GE(c.x, 4.f);
    EXPECT_GE(c.z, 1.f);
}

TEST(GltfMaterials, MaskBelowTheCutoffRemovesTheSurfaceForCameraAndShadowRays) {
    GltfWriter w = squareFile({{"alphaMode", "MASK"},
                               {"alphaCutoff", 0.5},
                               {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 0.25}}}}});
    Scene scene = w.load();
    const Material &m = scene.materials[0];
    EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
    EXPECT_TRUE(m.mayCutOut());
    // Seen from the camera: the background.
    scene.background = glm::vec3(0.25f, 0.5f, 0.75f);
    {
        const Tracer tracer(scene);
        RayCounters counters;
        const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
        EXPECT_EQ(c, scene.background);
    }
    // Above a cutoff of 0.2 the same surface is there.
    scene.materials[0].alphaCutoff = 0.2f;
    EXPECT_FALSE(scene.materials[0].mayCutOut());
    const Tracer tracer(scene);
    RayCounters counters;
    const glm::vec3 c = WhittedIntegrator(tracer).radiance({{0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
    EXPECT_NE(c, scene.background);
}

TEST(GltfMaterials, BlendIsSeeThroughWithoutRefraction) {
    Scene scene = squareFile({{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.0, 0.0, 0.25}}}}})
                      .load();
    const Material &m = scene.materials[0];
    EXPECT_EQ(m.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(m.transparency, 0.75f);
    EXPECT_FLOAT_EQ(m.ior, 1.f);
    EXPECT_TRUE(m.mayTransmit());
}

TEST(GltfMaterials, DoubleSidedIsRecorded) {
    EXPECT_TRUE(squareFile({{"doubleSided", true}}).load().materials[0].doubleSided);
    EXPECT_FALSE(squareFile(nlohmann::json::object()).load().materials[0].doubleSided);
}

namespace {

/// A UV sphere of radius 0.45 as glTF accessors: returns (positions, normals, indices).
std::array<int, 3> sphereAccessors(GltfWriter &w, int rings, int segments) {
    std::vector<float> pos, nrm;
    std::vector<std::uint16_t> idx;
    const double pi = 3.14159265358979323846;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const double theta = pi * r / rings, phi = 2 * pi * s / segments;
            const double x = std::sin(theta) * std::cos(phi), y = std::cos(theta), z = std::sin(theta) * std::sin(phi);
            for (double v : {x, y, z}) {
                pos.push_back(float(0.45 * v));
                nrm.push_back(float(v));
            }
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const auto a = std::uint16_t(r * (segments + 1) + s), b = std::uint16_t(a + segments + 1);
            for (std::uint16_t i : {a, std::uint16_t(a + 1), b, std::uint16_t(a + 1), std::uint16_t(b + 1), b})
                idx.push_back(i);
        }
    const int p = w.accessor(w.view(pos), 5126, pos.size() / 3, "VEC3");
    w.doc["accessors"][std::size_t(p)]["min"] = {-0.45, -0.45, -0.45};
    w.doc["accessors"][std::size_t(p)]["max"] = {0.45, 0.45, 0.45};
    const int n = w.accessor(w.view(nrm), 5126, nrm.size() / 3, "VEC3");
    const int i = w.indices16(idx);
    return {p, n, i};
}

} // namespace

TEST(GltfMaterials, MetallicRoughnessGridMatchesTheGoldenImage) {
    // Rows: metallic 0, 0.5, 1 (top to bottom); columns: roughness 0, 0.25, 0.5, 0.75, 1. A gold base colour.
    GltfWriter w;
    const auto [pos, nrm, idx] = sphereAccessors(w, 24, 48);
    std::vector<int> roots;
    const double metallic[] = {0.0, 0.5, 1.0};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 5; ++col) {
            const int material = int(w.doc["materials"].size());
            w.doc["materials"].push_back({{"pbrMetallicRoughness",
                                           {{"baseColorFactor", {1.0, 0.72, 0.3, 1.0}},
                                            {"metallicFactor", metallic[row]},
                                            {"roughnessFactor", 0.25 * col}}}});
            const int m = w.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}, {"material", material}});
            roots.push_back(w.node({{"mesh", m}, {"translation", {col - 2.0, 1.0 - row, 0.0}}}));
        }
    // A grey floor behind the spheres gives the mirrors something besides the background.
    const int floorPos = w.positions({-3, -1.6f, -1.5f, 3, -1.6f, -1.5f, 3, 1.6f, -1.5f, -3, 1.6f, -1.5f});
    w.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"metallicFactor", 0.0}}}});
    const int floorMesh = w.mesh({{"attributes", {{"POSITION", floorPos}}},
                                  {"indices", w.indices16({0, 1, 2, 0, 2, 3})},
                                  {"material", int(w.doc["materials"].size()) - 1}});
    roots.push_back(w.node({{"mesh", floorMesh}, {"extras", {{"layer", 0}}}}));
    w.scene(roots);
    const fs::path file = outDir() / "metallic-roughness-grid.gltf";
    std::ofstream(file) << w.text();
    const fs::path out = outDir() / "gltf-metallic-roughness.png";
    const fs::path golden = fs::path(MVCL_GOLDEN_DIR) / "gltf-metallic-roughness.png";
    fs::remove(out);
    const CommandResult r = runRender(quoted(file.string()) + " --size 300x200 --spp 4 --eye 0,0.6,7 --target 0,0,0 --fov 32 -o " +
                                      quoted(out.string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    MVCL_EXPECT_MATCHES_GOLDEN(out, golden);
    const Framebuffer image = readImage(out);
    // The rough metal (bottom right) is lit, not black: its centre is bright.
    const glm::vec3 roughMetal = image.pixels()[std::size_t(image.width()) * std::size_t(image.height() * 3 / 4) +
                                                std::size_t(image.width() * 5 / 6)];
    EXPECT_GT(luminance(roughMetal), 0.05f);
}
