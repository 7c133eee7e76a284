// glTF textures: PNG and JPEG decoded from memory (bufferView, data URI, external file through
// the sandbox), samplers (wrap, nearest/linear), KHR_texture_transform, TEXCOORD_1, mip levels
// from the ray footprint, alpha-mask textures that cut camera and shadow rays, limits against
// decompression bombs, and warnings (never a failed load) for textures that cannot be used.
// The Duck's golden image is rendered through mvcl-render (MVCL_UPDATE_GOLDEN=1 rewrites it).

#include "GltfTestWriter.h"
#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/GltfLoader.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <stb_image_write.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <fstream>

using namespace mvcl;
using namespace mvcl::test;
namespace fs = std::filesystem;

namespace {

/// stb_image_write's output callback: appends to a byte vector.
void appendBytes(void *context, void *data, int size) {
    auto *out = static_cast<std::vector<std::uint8_t> *>(context);
    const auto *bytes = static_cast<const std::uint8_t *>(data);
    out->insert(out->end(), bytes, bytes + size);
}

/// An RGBA image encoded as PNG or JPEG ("png"/"jpg", the JPEG at quality 98) in memory, keeping
/// its first `channels` channels.
std::vector<std::uint8_t> encode(int w, int h, const std::vector<std::uint8_t> &rgba, const char *ext,
                                 int channels = 4) {
    std::vector<std::uint8_t> pixels;
    for (int i = 0; i < w * h; ++i)
        for (int c = 0; c < channels; ++c) pixels.push_back(rgba[std::size_t(i * 4 + c)]);
    std::vector<std::uint8_t> out;
    const bool png = std::string(ext) == "png";
    EXPECT_TRUE(png ? stbi_write_png_to_func(appendBytes, &out, w, h, channels, pixels.data(), w * channels)
                    : stbi_write_jpg_to_func(appendBytes, &out, w, h, channels, pixels.data(), 98));
    return out;
}

std::vector<std::uint8_t> repeated(const std::array<std::uint8_t, 4> &texel, int count) {
    std::vector<std::uint8_t> out(std::size_t(count) * 4);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = texel[i % 4];
    return out;
}

/// 2×2 texels: red, green (top row), blue, white with alpha 0 (bottom row).
std::vector<std::uint8_t> quadrants() {
    return {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 0};
}

/// A 2×2 square at z = 0 facing +Z, uv (0,0) at the top left (−1, 1) to (1,1) at the bottom right
/// (1, −1); TEXCOORD_1 is TEXCOORD_0 mirrored left-right.
GltfWriter texturedSquare(const std::vector<std::uint8_t> &image, const char *mime, nlohmann::json material,
                          nlohmann::json sampler = nlohmann::json::object()) {
    GltfWriter w;
    const int pos = w.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
    const int uv0 = w.accessor(w.view(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}), 5126, 4, "VEC2");
    const int uv1 = w.accessor(w.view(std::vector<float>{1, 1, 0, 1, 0, 0, 1, 0}), 5126, 4, "VEC2");
    const int idx = w.indices16({0, 1, 2, 0, 2, 3});
    const int view = w.view(image);
    w.doc["images"].push_back({{"bufferView", view}, {"mimeType", mime}, {"name", "quadrants"}});
    w.doc["samplers"].push_back(sampler);
    w.doc["textures"].push_back({{"source", 0}, {"sampler", 0}});
    w.doc["materials"].push_back(material);
    const int m = w.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}},
                          {"indices", idx},
                          {"material", 0}});
    w.scene({w.node({{"mesh", m}})});
    return w;
}

nlohmann::json baseColorMaterial(nlohmann::json textureInfo = {{"index", 0}}) {
    return {{"pbrMetallicRoughness", {{"baseColorTexture", textureInfo}, {"metallicFactor", 0.0}}}};
}

const nlohmann::json kNearest = {{"magFilter", 9728}, {"minFilter", 9728}};

/// The diffuse colour the camera sees at (x, y): lit head-on by one light, no ambient.
glm::vec3 colourAt(Scene scene, float x, float y) {
    Light l;
    l.type = LightType::Directional;
    l.direction = glm::vec3(0.f, 0.f, -1.f);
    l.intensity = glm::vec3(1.f);
    scene.lights = {l};
    scene.ambientLight = glm::vec3(0.f);
    scene.background = glm::vec3(0.f, 0.f, 0.f);
    // Remove the highlight so that only P · (N·L) = P remains.
    for (Material &m : scene.materials) m.metallicRoughness.roughness = 1.f;
    const Tracer tracer(scene);
    RayCounters counters;
    return WhittedIntegrator(tracer).radiance({{x, y, 5.f}, {0.f, 0.f, -1.f}}, {}, counters) - glm::vec3(0.04f);
}

void expectNear(const glm::vec3 &a, const glm::vec3 &b, float tolerance, const char *what) {
    EXPECT_NEAR(a.x, b.x, tolerance) << what;
    EXPECT_NEAR(a.y, b.y, tolerance) << what;
    EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

} // namespace

TEST(GltfTextures, BaseColorPngFromABufferViewIsSampledPerTexel) {
    const Scene scene =
        texturedSquare(encode(2, 2, quadrants(), "png"), "image/png", baseColorMaterial(), kNearest).load();
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.report.texturesDecoded, 1u);
    EXPECT_GT(scene.report.textureBytes, 0u);
    expectNear(colourAt(scene, -0.5f, 0.5f), {1, 0, 0}, 0.01f, "top left red");
    expectNear(colourAt(scene, 0.5f, 0.5f), {0, 1, 0}, 0.01f, "top right green");
    expectNear(colourAt(scene, -0.5f, -0.5f), {0, 0, 1}, 0.01f, "bottom left blue");
}

TEST(GltfTextures, JpegDecodesAndDataUriImagesAreRead) {
    // An 8×8 JPEG of one colour (JPEG is lossy: compare loosely); given as a data URI.
    const std::vector<std::uint8_t> orange = repeated({255, 128, 0, 255}, 64);
    GltfWriter w = texturedSquare(encode(2, 2, quadrants(), "png"), "image/png", baseColorMaterial(), kNearest);
    w.doc["images"][0] = {{"uri", "data:image/jpeg;base64," + base64(encode(8, 8, orange, "jpg", 3))}};
    const Scene scene = w.load();
    ASSERT_EQ(scene.textures.size(), 1u);
    const glm::vec3 c = colourAt(scene, 0.f, 0.f);
    EXPECT_NEAR(c.x, 1.f, 0.05f);
    EXPECT_NEAR(c.y, 0.216f, 0.05f); // sRGB 128 is linear 0.216
    EXPECT_NEAR(c.z, 0.f, 0.05f);
}

TEST(GltfTextures, ExternalImagesAreReadThroughTheSandbox) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-texture-external";
    fs::create_directories(dir);
    const std::vector<std::uint8_t> png = encode(2, 2, quadrants(), "png");
    std::ofstream(dir / "quadrants.png", std::ios::binary).write(reinterpret_cast<const char *>(png.data()),
                                                                  std::streamsize(png.size()));
    GltfWriter w = texturedSquare(png, "image/png", baseColorMaterial(), kNearest);
    w.doc["images"][0] = {{"uri", "quadrants.png"}};
    const std::string text = w.text();
    const Scene scene = loadGltfFromMemory(asBytes(text), "external.gltf", dir);
    ASSERT_EQ(scene.textures.size(), 1u);
    expectNear(colourAt(scene, 0.5f, 0.5f), {0, 1, 0}, 0.01f, "top right green");
    // A path out of the folder is refused by the sandbox, as for buffers.
    w.doc["images"][0] = {{"uri", "../quadrants.png"}};
    const std::string escaping = w.text();
    EXPECT_THROW(loadGltfFromMemory(asBytes(escaping), "escaping.gltf", dir), Error);
}

TEST(GltfTextures, WrapModesAndTextureTransformAndSecondTexcoords) {
    const std::vector<std::uint8_t> png = encode(2, 2, quadrants(), "png");
    // Offset by half the texture to the right: with REPEAT, the top left shows green.
    nlohmann::json shifted = {{"index", 0},
                              {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}}}}}};
    const Scene repeat = texturedSquare(png, "image/png", baseColorMaterial(shifted), kNearest).load();
    expectNear(colourAt(repeat, -0.5f, 0.5f), {0, 1, 0}, 0.01f, "repeat: green wraps to the left");
    expectNear(colourAt(repeat, 0.5f, 0.5f), {1, 0, 0}, 0.01f, "repeat: red wraps to the right");
    nlohmann::json clamp = kNearest;
    clamp["wrapS"] = 33071;
    const Scene clamped = texturedSquare(png, "image/png", baseColorMaterial(shifted), clamp).load();
    expectNear(colourAt(clamped, 0.5f, 0.5f), {0, 1, 0}, 0.01f, "clamp: the edge texel repeats");
    nlohmann::json mirror = kNearest;
    mirror["wrapS"] = 33648;
    const Scene mirrored = texturedSquare(png, "image/png", baseColorMaterial(shifted), mirror).load();
    expectNear(colourAt(mirrored, 0.5f, 0.5f), {0, 1, 0}, 0.01f, "mirrored: green again past the edge");
    const Scene second = texturedSquare(png, "image/png", baseColorMaterial({{"index", 0}, {"texCoord", 1}}), kNearest).load();
    expectNear(colourAt(second, -0.5f, 0.5f), {0, 1, 0}, 0.01f, "TEXCOORD_1 is mirrored left-right");
}

TEST(GltfTextures, LinearFilteringBlendsNeighboursAndMipLevelsAverage) {
    const Scene scene = texturedSquare(encode(2, 2, quadrants(), "png"), "image/png", baseColorMaterial(),
                                       {{"magFilter", 9729}, {"minFilter", 9987}})
                            .load();
    const Texture &t = scene.textures[0];
    ASSERT_EQ(t.image->levelCount(), 2);
    // Between the red and green texel centres: half of each (filtered in linear space).
    const glm::vec4 mid = t.sample({0.5f, 0.25f}, 0.f, TextureColorSpace::Srgb);
    EXPECT_NEAR(mid.r, 0.5f, 0.01f);
    EXPECT_NEAR(mid.g, 0.5f, 0.01f);
    // A footprint of two texels or more reads the 1×1 level: the average of all four, in linear
    // light (red is 1 in two of the four texels).
    const glm::vec4 coarse = t.sample({0.1f, 0.1f}, 4.f, TextureColorSpace::Srgb);
    EXPECT_NEAR(coarse.r, 0.5f, 0.01f);
    EXPECT_NEAR(coarse.a, 0.75f, 0.01f);
}

TEST(GltfTextures, DistantTexturesUseCoarserLevelsFromTheRayCone) {
    // A 256×256 checkerboard of single texels: a ray cone far wider than a texel must read the
    // grey average, not one black or white texel (which is what aliasing looks like).
    std::vector<std::uint8_t> checker(256 * 256 * 4, 255);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            for (int c = 0; c < 3; ++c) checker[std::size_t((y * 256 + x) * 4 + c)] = (x + y) % 2 ? 255 : 0;
    Scene scene = texturedSquare(encode(256, 256, checker, "png"), "image/png", baseColorMaterial()).load();
    for (Material &m : scene.materials) m.metallicRoughness.roughness = 1.f;
    scene.ambientLight = glm::vec3(1.f);
    scene.lights.clear();
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    RayCounters counters;
    // At the centre of texel (128, 126), so that the bilinear filter reads it alone.
    Ray thin{{128.5f / 128.f - 1.f, 1.f - 126.5f / 128.f, 5.f}, {0.f, 0.f, -1.f}};
    Ray wide = thin;
    wide.coneSpread = 0.05f; // 0.25 wide at the square: 32 texels
    const float thinValue = integrator.radiance(thin, {}, counters).x;
    const float wideValue = integrator.radiance(wide, {}, counters).x;
    EXPECT_TRUE(thinValue < 0.05f || thinValue > 0.95f) << thinValue;
    EXPECT_NEAR(wideValue, 0.5f, 0.1f); // levels average in linear light: half of white
}

TEST(GltfTextures, AlphaMaskTextureCutsCameraAndShadowRays) {
    // The quadrants' bottom right texel has alpha 0: it is a hole for every ray.
    GltfWriter w = texturedSquare(encode(2, 2, quadrants(), "png"), "image/png",
                                  {{"alphaMode", "MASK"},
                                   {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}}},
                                  kNearest);
    // A floor below the square (z = −1), facing the light.
    const int floorPos = w.positions({-4, -4, -1, 4, -4, -1, 4, 4, -1, -4, 4, -1});
    w.doc["materials"].push_back({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
    const int floorMesh = w.mesh({{"attributes", {{"POSITION", floorPos}}}, {"indices", w.indices16({0, 1, 2, 0, 2, 3})}, {"material", 1}});
    w.doc["scenes"][0]["nodes"].push_back(w.node({{"mesh", floorMesh}}));
    Scene scene = w.load();
    Light l;
    l.type = LightType::Directional;
    l.direction = glm::vec3(0.f, 0.f, -1.f);
    l.intensity = glm::vec3(1.f);
    scene.lights = {l};
    scene.ambientLight = glm::vec3(0.f);
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    RayCounters counters;
    // Through the hole: the lit floor (white diffuse). Through the opaque blue: blue.
    const glm::vec3 hole = integrator.radiance({{0.5f, -0.5f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
    const glm::vec3 blue = integrator.radiance({{-0.5f, -0.5f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters);
    EXPECT_GT(hole.x, 0.9f);
    EXPECT_GT(blue.z, 0.9f);
    EXPECT_LT(blue.x, 0.1f);
    // On the floor, seen from the side: lit under the hole, in shadow under the opaque part.
    const glm::vec3 underHole = integrator.radiance({{0.5f, -0.5f, 0.f}, {0.f, 0.f, -1.f}}, {}, counters);
    const glm::vec3 underBlue = integrator.radiance({{-0.5f, -0.5f, -0.5f}, {0.f, 0.f, -1.f}}, {}, counters);
    EXPECT_GT(underHole.x, 0.9f);
    EXPECT_LT(underBlue.x, 0.1f);
}

TEST(GltfTextures, UnusableImagesWarnAndUseTheFactor) {
    const std::vector<std::uint8_t> png = encode(2, 2, quadrants(), "png");
    const nlohmann::json material = {{"pbrMetallicRoughness",
                                      {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"metallicFactor", 0.0}}}};
    const auto warningWith = [](const Scene &s, const std::string &needle) {
        return std::any_of(s.report.warnings.begin(), s.report.warnings.end(),
                           [&](const std::string &w) { return w.find(needle) != std::string::npos; });
    };
    // Too many pixels (a decompression bomb is refused before decoding).
    GltfLoadOptions small;
    small.maxTexturePixels = 3;
    const Scene bomb = texturedSquare(png, "image/png", material).load(small);
    EXPECT_TRUE(bomb.textures.empty());
    EXPECT_TRUE(warningWith(bomb, "image 0 'quadrants' is 2×2 pixels, more than the limit of 3")) << bomb.report.warnings.front();
    EXPECT_EQ(bomb.materials[0].metallicRoughness.baseColor, glm::vec3(0.5f));
    // Garbage bytes behind a PNG signature.
    std::vector<std::uint8_t> broken(64, 0xAB);
    std::copy(png.begin(), png.begin() + 16, broken.begin());
    const Scene corrupt = texturedSquare(broken, "image/png", material).load();
    EXPECT_TRUE(corrupt.textures.empty());
    EXPECT_TRUE(warningWith(corrupt, "baseColorTexture: image 0 'quadrants' cannot be decoded as PNG"));
    // A KTX2 image is named.
    std::vector<std::uint8_t> ktx2(64, 0);
    const char magic[] = "\xABKTX 20\xBB\r\n\x1A\n";
    std::copy(magic, magic + 12, ktx2.begin());
    const Scene compressed = texturedSquare(ktx2, "image/ktx2", material).load();
    EXPECT_TRUE(warningWith(compressed, "is a KTX2 image, which mvcl does not decode"));
    // A texture index that does not exist.
    GltfWriter w = texturedSquare(png, "image/png", material);
    w.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 7;
    EXPECT_TRUE(warningWith(w.load(), "refers to texture 7, which does not exist"));
    // A sampled factor colour stays what the surface shows.
    expectNear(colourAt(bomb, 0.f, 0.f), glm::vec3(0.5f), 0.01f, "factor colour");
}

TEST(GltfTextures, NormalMapsTiltTheShadingNormalWithGeneratedTangents) {
    // A flat normal map pointing +u at 45°: (0.5 + 0.5·0.707, 0.5, 0.5 + 0.5·0.707).
    const std::vector<std::uint8_t> tilted = repeated({218, 128, 218, 255}, 4);
    GltfWriter w = texturedSquare(encode(2, 2, tilted, "png"), "image/png",
                                  {{"normalTexture", {{"index", 0}}}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
    Scene scene = w.load();
    ASSERT_EQ(scene.meshes[0].tangents.size(), scene.meshes[0].positions.size());
    // u grows with x on the square: the tangent is +X.
    EXPECT_NEAR(scene.meshes[0].tangents[0].x, 1.f, 1e-5f);
    // Light from +X at a grazing 60° from the normal: the tilted normal faces it more.
    Light l;
    l.type = LightType::Directional;
    l.direction = glm::normalize(glm::vec3(-0.866f, 0.f, -0.5f));
    l.intensity = glm::vec3(1.f);
    scene.lights = {l};
    scene.ambientLight = glm::vec3(0.f);
    scene.materials[0].metallicRoughness.roughness = 1.f;
    const Tracer tracer(scene);
    RayCounters counters;
    const float lit = WhittedIntegrator(tracer).radiance({{0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}}, {}, counters).x;
    EXPECT_GT(lit, 0.8f); // cos 15° ≈ 0.97 instead of cos 60° = 0.5
}

TEST(GltfTextures, MaterialFeaturesMatchTheGoldenImage) {
    // Left: a card with a checkerboard alpha mask casting a checkered shadow on the floor; middle:
    // an emissive square glowing orange; right: a transmissive (KHR_materials_transmission, ior
    // 1.5) block refracting the floor. Default key and fill lights, through mvcl-render.
    std::vector<std::uint8_t> mask(8 * 8 * 4, 255);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            std::uint8_t *t = mask.data() + (y * 8 + x) * 4;
            t[0] = 40;
            t[1] = 120;
            t[2] = 220;
            t[3] = (x + y) % 2 ? 255 : 0;
        }
    GltfWriter w = texturedSquare(encode(8, 8, mask, "png"), "image/png",
                                  {{"alphaMode", "MASK"},
                                   {"doubleSided", true},
                                   {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}}},
                                  kNearest);
    w.doc["nodes"][0]["translation"] = {-2.4, 0.0, 0.0};
    const auto square = [&](nlohmann::json material, std::vector<double> translation, std::vector<double> scale) {
        const int index = int(w.doc["materials"].size());
        w.doc["materials"].push_back(material);
        nlohmann::json prim = w.doc["meshes"][0]["primitives"][0];
        prim["material"] = index;
        const int mesh = w.mesh(prim);
        w.doc["scenes"][0]["nodes"].push_back(w.node({{"mesh", mesh}, {"translation", translation}, {"scale", scale}}));
    };
    square({{"emissiveFactor", {1.0, 0.45, 0.1}}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.1, 0.1, 1.0}}, {"metallicFactor", 0.0}}}},
           {0.0, 0.0, 0.0}, {0.8, 0.8, 1.0});
    // The floor: a square turned to lie in y = −1.2, seen from above and in front.
    const int floorMaterial = int(w.doc["materials"].size());
    w.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.75, 1.0}}, {"metallicFactor", 0.0}}}});
    nlohmann::json floorPrim = w.doc["meshes"][0]["primitives"][0];
    floorPrim["material"] = floorMaterial;
    const int floorMesh = w.mesh(floorPrim);
    w.doc["scenes"][0]["nodes"].push_back(w.node({{"mesh", floorMesh},
                                                  {"translation", {0.0, -1.2, 0.0}},
                                                  {"rotation", {-0.7071068, 0.0, 0.0, 0.7071068}},
                                                  {"scale", {5.0, 3.0, 1.0}}}));
    // The glass block: a closed box from the metallic-roughness grid's sphere helper would do, but
    // two squares (front and back) of a thin slab are enough to refract.
    const int glass = int(w.doc["materials"].size());
    w.doc["materials"].push_back({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.1}}},
                                  {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}},
                                                  {"KHR_materials_ior", {{"ior", 1.5}}}}}});
    const int boxPos = w.positions({-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1, -1, -1, 1, 1, -1, 1, -1, 1, 1, 1, 1, 1});
    const int boxIdx = w.indices16({0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5});
    const int boxMesh = w.mesh({{"attributes", {{"POSITION", boxPos}}}, {"indices", boxIdx}, {"material", glass}});
    w.doc["scenes"][0]["nodes"].push_back(w.node({{"mesh", boxMesh}, {"translation", {2.4, -0.2, 0.4}}, {"scale", {0.8, 1.0, 0.5}}}));
    w.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_ior"};

    const fs::path file = outDir() / "material-features.gltf";
    std::ofstream(file) << w.text();
    const fs::path out = outDir() / "gltf-material-features.png";
    const fs::path golden = fs::path(MVCL_GOLDEN_DIR) / "gltf-material-features.png";
    fs::remove(out);
    const CommandResult r = runRender(quoted(file.string()) + " --size 300x160 --spp 4 --eye 0,2.5,7 --target 0,-0.4,0 --fov 40 -o " +
                                      quoted(out.string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    MVCL_EXPECT_MATCHES_GOLDEN(out, golden);
}

namespace {

/// Renders a model of tests/data/models through mvcl-render and compares it with
/// tests/golden/gltf-<name>.png; returns the image (empty when the golden was rewritten).
Framebuffer renderModelAgainstGolden(const std::string &name, const std::string &file) {
    const fs::path out = outDir() / ("gltf-" + name + ".png");
    const fs::path golden = fs::path(MVCL_GOLDEN_DIR) / ("gltf-" + name + ".png");
    fs::remove(out);
    const CommandResult r = runRender(quoted(dataPath("models/" + file)) + " --size 200x200 --spp 4 -o " +
                                      quoted(out.string()));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("Texture"), std::string::npos) << r.output; // no texture warning
    if (updateGoldenRequested()) {
        fs::copy_file(out, golden, fs::copy_options::overwrite_existing);
        return Framebuffer();
    }
    EXPECT_TRUE(fs::exists(golden)) << golden << " is missing; run with MVCL_UPDATE_GOLDEN=1";
    const Framebuffer image = readImage(out);
    const ImageDifference diff = compareImages(image, readImage(golden), 8);
    EXPECT_LT(diff.differingFraction, 0.002) << name << ": max channel delta " << diff.maxChannelDelta;
    return image;
}

} // namespace

TEST(GltfTextures, DuckMatchesTheGoldenImage) {
    const Framebuffer image = renderModelAgainstGolden("Duck", "Duck/Duck.glb");
    if (image.pixels().empty()) GTEST_SKIP() << "golden image rewritten";
    // The body is yellow (red and green well above blue), as the texture says.
    const glm::vec3 body = image.pixels()[std::size_t(image.width()) * std::size_t(image.height() * 2 / 3) +
                                          std::size_t(image.width() / 2)];
    EXPECT_GT(body.x, 2.f * body.z);
    EXPECT_GT(body.y, 2.f * body.z);
}

TEST(GltfTextures, AvocadoWithGltfDefaultMaterialIsNotBlack) {
    // This copy of the Avocado has no textures and `pbrMetallicRoughness: {}`: a rough white metal.
    const Framebuffer image = renderModelAgainstGolden("Avocado", "Avocado/Avocado.glb");
    if (image.pixels().empty()) GTEST_SKIP() << "golden image rewritten";
    const glm::vec3 centre = image.pixels()[std::size_t(image.width()) * std::size_t(image.height() / 2) +
                                            std::size_t(image.width() / 2)];
    EXPECT_GT(centre.x + centre.y + centre.z, 1.f);
}
