// The POV-Ray scene of `mvcl-bench pov`: each of our Phong/Whitted terms lands on its POV-Ray
// counterpart (PovScene.h's table), what cannot be converted is said, the file has every object of
// the scene in world space, and the level difference of `mvcl-bench image-diff` counts 8-bit levels.

#include "ImageError.h"
#include "PovScene.h"

#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/ImageIO.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace mvcl::bench {
namespace {

std::size_t count(const std::string &text, const std::string &what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

bool mentions(const std::vector<std::string> &notes, const std::string &what) {
    for (const std::string &note : notes)
        if (note.find(what) != std::string::npos) return true;
    return false;
}

TEST(PovScene, OpaqueMaterialIsPigmentAmbientSpecularAndReflection) {
    Material m;
    m.diffuse = {0.5f, 0.25f, 0.1f};
    m.ambient = {0.5f, 0.25f, 0.1f};
    m.specular = 0.4f;
    m.shininess = 40.f;
    m.reflectivity = 0.15f;
    const PovMaterial p = povMaterialOf(m, glm::vec3(0.12f));
    EXPECT_EQ(p.pigment, glm::dvec3(m.diffuse));
    EXPECT_EQ(p.diffuse, 1.0);
    EXPECT_EQ(p.transmit, 0.0);
    // POV multiplies the finish's ambient by the pigment: A·ambientLight / P.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.ambient[c], double(0.12f), 1e-7);
    EXPECT_DOUBLE_EQ(p.specular, double(0.4f));
    EXPECT_DOUBLE_EQ(p.roughness, 1.0 / 40.0);
    EXPECT_EQ(p.reflectionMin, glm::dvec3(double(0.15f)));
    EXPECT_FALSE(p.fresnel);
    EXPECT_TRUE(p.lost.empty());
}

TEST(PovScene, GlassTransmitsWithFresnelReflectionAndADimmedHighlight) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const Material &glass = scene.materials[4];
    ASSERT_EQ(glass.name, "glass");
    const PovMaterial p = povMaterialOf(glass, scene.ambientLight);
    EXPECT_DOUBLE_EQ(p.transmit, double(0.92f));
    EXPECT_TRUE(p.fresnel);
    EXPECT_DOUBLE_EQ(p.ior, 1.5);
    // Our highlight is scaled by 1 − T with the rest of the local light, POV's is not: Ks·(1 − T).
    EXPECT_DOUBLE_EQ(p.specular, double(0.9f) * (1.0 - double(0.92f)));
    // Reflected R + T·F: from R·S at normal incidence (F = 0) to R·S + T at grazing (F = 1).
    EXPECT_EQ(p.reflectionMin, glm::dvec3(0.0));
    EXPECT_EQ(p.reflectionMax, glm::dvec3(double(0.92f)));
}

TEST(PovScene, MetalWithoutDiffuseCarriesItsAmbientInThePigment) {
    Material m;
    m.diffuse = glm::vec3(0.f);
    m.ambient = {0.6f, 0.3f, 0.2f};
    m.specular = 1.f;
    m.specularColor = {0.9f, 0.5f, 0.3f};
    m.reflectivity = 0.7f;
    const PovMaterial p = povMaterialOf(m, glm::vec3(0.5f));
    EXPECT_EQ(p.diffuse, 0.0);
    EXPECT_EQ(p.pigment, glm::dvec3(m.ambient) * 0.5);
    EXPECT_EQ(p.ambient, glm::dvec3(1.0));
    // The mirror is tinted, the highlight cannot be: said so.
    EXPECT_EQ(p.reflectionMin, double(0.7f) * glm::dvec3(m.specularColor));
    EXPECT_TRUE(mentions(p.lost, "tint"));
}

TEST(PovScene, EmissionIsUndoneFromPigmentAndOpacity) {
    Material m;
    m.diffuse = glm::vec3(0.5f);
    m.ambient = glm::vec3(0.f);
    m.emission = glm::vec3(2.f, 1.f, 0.f);
    m.transparency = 0.5f;
    const PovMaterial p = povMaterialOf(m, glm::vec3(0.1f));
    // POV emits pigment × emission × (1 − T); ours is E as it is.
    EXPECT_DOUBLE_EQ(p.emission.x, 2.0 / (0.5 * 0.5));
    EXPECT_DOUBLE_EQ(p.emission.y, 1.0 / (0.5 * 0.5));
    EXPECT_EQ(p.emission.z, 0.0);
    EXPECT_TRUE(p.lost.empty());
}

TEST(PovScene, TexturesAndAlphaMasksAreNamedAsNotConverted) {
    Material m;
    m.hasMetallicRoughness = true;
    m.metallicRoughness.baseColorTexture.texture = 0;
    m.alphaMode = AlphaMode::Mask;
    const PovMaterial p = povMaterialOf(m, glm::vec3(0.1f));
    EXPECT_TRUE(mentions(p.lost, "textures"));
    EXPECT_TRUE(mentions(p.lost, "alpha mask"));
}

TEST(PovScene, HorizontalAngleFromVerticalFieldOfView) {
    EXPECT_NEAR(povHorizontalAngle(40.0, 1.0), 40.0, 1e-12);
    EXPECT_NEAR(povHorizontalAngle(90.0, 2.0), 2.0 * std::atan(2.0) * 180.0 / std::numbers::pi, 1e-12);
}

TEST(PovScene, CubeInCubeHasEveryObjectLightAndSetting) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    std::ostringstream out;
    PovSceneOptions options;
    options.source = "builtin:cube-in-cube";
    options.width = 500;
    options.height = 500;
    options.maxDepth = 8;
    const PovSceneSummary summary = writePovScene(out, scene, camera, options);
    const std::string text = out.str();
    EXPECT_EQ(summary.meshes, 2u);
    EXPECT_EQ(summary.triangles, 24u);
    EXPECT_EQ(summary.spheres, 2u);
    EXPECT_EQ(summary.planes, 1u);
    EXPECT_EQ(summary.lights, 1u);
    EXPECT_EQ(summary.materials, 5u);
    EXPECT_TRUE(summary.notes.empty());
    EXPECT_EQ(count(text, "mesh2 {"), 2u);
    EXPECT_EQ(count(text, "sphere {"), 2u);
    EXPECT_EQ(count(text, "plane {"), 1u);
    EXPECT_EQ(count(text, "light_source {"), 1u);
    EXPECT_NE(text.find("max_trace_level 9"), std::string::npos);
    EXPECT_NE(text.find("adc_bailout 0"), std::string::npos);
    EXPECT_NE(text.find("assumed_gamma 1.0"), std::string::npos);
    EXPECT_NE(text.find("location <0.5, 3.6, 7.5>"), std::string::npos);
    EXPECT_NE(text.find("look_at <0, 0.9, 0>"), std::string::npos);
    EXPECT_NE(text.find("interior { ior 1.5 }"), std::string::npos);
    EXPECT_NE(text.find("Not converted: textures"), std::string::npos);
}

TEST(PovScene, WorldSpaceIsSceneSpacePlusTheOriginAndDirectionalLightsAreParallel) {
    Scene scene;
    scene.worldOrigin = {100.0, 0.0, -50.0};
    scene.materials.push_back(Material{});
    TriangleMesh mesh;
    mesh.positions = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}};
    mesh.normals = {{0.f, 0.f, 1.f}, {0.f, 0.f, 1.f}, {0.f, 0.f, 1.f}};
    mesh.indices = {{0, 1, 2}};
    scene.meshes.push_back(mesh);
    Plane plane;
    plane.normal = {0.f, 0.f, 1.f};
    plane.offset = 2.f;
    scene.planes.push_back(plane);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.f, -1.f, 0.f};
    scene.lights.push_back(sun);
    std::ostringstream out;
    writePovScene(out, scene, Camera::lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f), {});
    const std::string text = out.str();
    EXPECT_NE(text.find("<101, 0, -50>"), std::string::npos);
    EXPECT_NE(text.find("normal_vectors { 3,"), std::string::npos);
    EXPECT_NE(text.find("<0, 0, 1>, -48"), std::string::npos); // z = 2 in scene space is z = −48
    EXPECT_NE(text.find("parallel"), std::string::npos);
    EXPECT_NE(text.find("location <100, 0, -45>"), std::string::npos);
}

TEST(PovScene, ASceneWithoutMaterialsGetsTheDefaultOne) {
    Scene scene;
    scene.spheres.push_back({"ball", {0.f, 0.f, 0.f}, 1.f, 3, 0});
    std::ostringstream out;
    const PovSceneSummary summary =
        writePovScene(out, scene, Camera::lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f), {});
    EXPECT_EQ(summary.materials, 1u);
    EXPECT_NE(out.str().find("material { MvclMaterial0 }"), std::string::npos);
}

TEST(PovScene, InverseSquarePointLightBecomesAFade) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.spheres.push_back({"ball", {0.f, 0.f, 0.f}, 1.f, 0, 0});
    Light bulb;
    bulb.position = {0.f, 4.f, 0.f};
    bulb.intensity = glm::vec3(8.f);
    bulb.constantAttenuation = 1.f;
    bulb.quadraticAttenuation = 0.25f;
    scene.lights.push_back(bulb);
    std::ostringstream out;
    const PovSceneSummary summary =
        writePovScene(out, scene, Camera::lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f), {});
    // I / (1 + r²/4) = (I / 2) · 2 / (1 + (r / 2)²): colour 4, fade_distance 2, fade_power 2, exact.
    const std::string text = out.str();
    EXPECT_NE(text.find("color rgb <4, 4, 4>"), std::string::npos);
    EXPECT_NE(text.find("fade_distance 2"), std::string::npos);
    EXPECT_NE(text.find("fade_power 2"), std::string::npos);
    EXPECT_TRUE(summary.notes.empty());
}

TEST(LevelDifference, CountsEightBitLevels) {
    Framebuffer a(2, 1), b(2, 1);
    a.at(0, 0) = glm::vec3(0.f);
    b.at(0, 0) = glm::vec3(srgbToLinear(10.f / 255.f), 0.f, 0.f);
    a.at(1, 0) = b.at(1, 0) = glm::vec3(0.5f);
    const LevelDifference d = levelDifference(a, b, 8);
    EXPECT_EQ(d.max, 10);
    EXPECT_DOUBLE_EQ(d.mean, 10.0 / 6.0);
    EXPECT_DOUBLE_EQ(d.shareAbove, 0.5);
    EXPECT_EQ(levelDifference(a, a).max, 0);
    // Every level survives the round trip through linear light that readImage() makes.
    for (int level = 0; level < 256; ++level) {
        Framebuffer one(1, 1), other(1, 1);
        one.at(0, 0) = glm::vec3(srgbToLinear(float(level) / 255.f));
        other.at(0, 0) = glm::vec3(level == 255 ? 1.f : srgbToLinear(float(level + 1) / 255.f));
        EXPECT_EQ(levelDifference(one, other).max, level == 255 ? 0 : 1) << level;
    }
}

} // namespace
} // namespace mvcl::bench
