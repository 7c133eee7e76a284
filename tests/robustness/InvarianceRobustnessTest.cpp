// Catalogue section B, cases 19 and 20: scale invariance (the offsets scale with the geometry:
// no fixed epsilon) and translation invariance (the glTF loader re-centres in double; built
// scenes that skip re-centring lose float precision with distance, which is measured).

#include "TestRender.h"
#include "ImageCompare.h"

#include "tracer/TracerTestUtil.h"

#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace mvcl {
namespace {

void measured(const std::string &line) { std::printf("[ measured ] %s\n", line.c_str()); }

constexpr int kWidth = 48, kHeight = 36;

/// A glass cube around a red cube, a mirror sphere and a floor, lit by a point light without
/// distance fall-off, all scaled by k about `centre` (computed in double, rounded to float).
Scene makeInvarianceScene(double k, const glm::dvec3 &centre) {
    Scene scene;
    Material glass;
    glass.diffuse = glass.ambient = glm::vec3(0.2f, 0.3f, 0.8f);
    glass.transparency = 0.6f;
    glass.ior = 1.3f;
    glass.specular = 0.5f;
    Material red;
    red.diffuse = red.ambient = glm::vec3(0.9f, 0.2f, 0.1f);
    Material mirror;
    mirror.diffuse = mirror.ambient = glm::vec3(0.1f);
    mirror.reflectivity = 0.8f;
    Material floor;
    floor.diffuse = floor.ambient = glm::vec3(0.6f);
    scene.materials = {glass, red, mirror, floor};
    auto at = [&](double x, double y, double z) { return glm::vec3(centre + k * glm::dvec3(x, y, z)); };
    TriangleMesh outer = test::makeBoxMesh(at(-1, -1, -1), at(1, 1, 1));
    outer.material = 0;
    TriangleMesh inner = test::makeBoxMesh(at(-0.5, -0.5, -0.5), at(0.5, 0.5, 0.5));
    inner.material = 1;
    inner.layer = 1;
    scene.meshes = {outer, inner};
    scene.spheres.push_back({"mirror", at(-2.2, -0.4, 0.3), float(0.6 * k), 2, 0});
    Plane plane;
    plane.normal = {0.f, 1.f, 0.f};
    plane.offset = float(centre.y - k);
    plane.material = 3;
    scene.planes.push_back(plane);
    Light light;
    light.position = at(2, 4, 3);
    scene.lights.push_back(light);
    scene.ambientLight = glm::vec3(0.1f);
    return scene;
}

test::TestRender renderInvarianceScene(double k, const glm::dvec3 &centre) {
    const Scene scene = makeInvarianceScene(k, centre);
    const Tracer tracer(scene);
    const Camera camera = Camera::lookAt(glm::vec3(centre + k * glm::dvec3(3, 2, 5)), glm::vec3(centre),
                                         {0.f, 1.f, 0.f}, 45.f);
    return test::renderWithPolicy(tracer, camera, kWidth, kHeight, 1, 0);
}

/// Case 19: k ∈ [1e-7, 1e7] against k = 1 (mean absolute difference of linear radiance). Any
/// change of k moves silhouettes and shadow edges by rounding, which flips a few edge pixels
/// (~2 %); k = 10 measures that rounding noise, and every other k must stay within twice it. A
/// fixed epsilon shows up as acne or missing layers over whole surfaces, far above that.
TEST(RobustnessInvariance, ImageIsScaleInvariantFromOneTenMillionthToTenMillion) {
    const auto reference = renderInvarianceScene(1.0, glm::dvec3(0.0));
    const double noise = test::meanAbsDifference(renderInvarianceScene(10.0, glm::dvec3(0.0)).image, reference.image);
    std::string table = "scale invariance: k, mean |diff| vs k=1, share of pixels off by > 2/255\n";
    double worst = 0;
    for (const double k : {1e-7, 1e-5, 1e-3, 1e-1, 1e3, 1e5, 1e7}) {
        const auto r = renderInvarianceScene(k, glm::dvec3(0.0));
        const double diff = test::meanAbsDifference(r.image, reference.image);
        const test::ImageDifference d = test::compareImages(r.image, reference.image, 2);
        worst = std::max(worst, diff);
        char row[96];
        std::snprintf(row, sizeof row, "  %-6.0e %.2e %.4f\n", k, diff, d.differingFraction);
        table += row;
        EXPECT_EQ(test::nonFinitePixels(r.image) + r.stats.rays.nonFiniteSamples, 0u) << "k=" << k;
        EXPECT_LE(diff, 2.0 * noise + 1e-4) << "k=" << k;
        EXPECT_LT(d.differingFraction, 0.05) << "k=" << k;
    }
    std::printf("%s", table.c_str());
    measured("scale invariance: rounding noise (k=10) " + std::to_string(noise) + ", worst mean |diff| = " +
             std::to_string(worst));
}

std::string base64(const std::vector<uint8_t> &bytes) {
    static const char *alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t n = uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0u) |
                           (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0u);
        out += alphabet[(n >> 18) & 63];
        out += alphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
    }
    return out;
}

/// Two unit cubes (one shared mesh; the second node scaled by 0.5 and moved aside) at glTF
/// translation t, as a .gltf with an embedded buffer.
std::string cubesGltf(const glm::dvec3 &t) {
    std::vector<uint8_t> buffer;
    auto put = [&](const void *data, std::size_t n) {
        const auto *p = static_cast<const uint8_t *>(data);
        buffer.insert(buffer.end(), p, p + n);
    };
    const TriangleMesh box = test::makeBoxMesh(glm::vec3(-1.f), glm::vec3(1.f));
    for (const glm::vec3 &p : box.positions) put(&p, sizeof p);
    for (const glm::uvec3 &tri : box.indices)
        for (int k = 0; k < 3; ++k) {
            const uint16_t index = uint16_t(tri[k]);
            put(&index, sizeof index);
        }
    char translation[2][160];
    std::snprintf(translation[0], sizeof translation[0], "[%.17g,%.17g,%.17g]", t.x, t.y, t.z);
    std::snprintf(translation[1], sizeof translation[1], "[%.17g,%.17g,%.17g]", t.x + 2.5, t.y - 0.25, t.z + 0.5);
    return std::string(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],)") +
           R"("buffers":[{"byteLength":168,"uri":"data:application/octet-stream;base64,)" + base64(buffer) + R"("}],)" +
           R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":72}],)" +
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[-1,-1,-1],"max":[1,1,1]},)" +
           R"({"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}],)" +
           R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.2,0.4,0.9,1]}},{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.2,0.1,1]}}],)" +
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]},)" +
           R"({"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":1}]}],)" +
           R"("nodes":[{"mesh":0,"translation":)" + translation[0] + R"(,"extras":{"layer":0}},)" +
           R"({"mesh":1,"translation":)" + translation[1] + R"(,"scale":[0.5,0.5,0.5],"extras":{"layer":1}}]})";
}

test::TestRender renderLoadedCubes(const glm::dvec3 &t, glm::dvec3 &worldOrigin) {
    const std::string json = cubesGltf(t);
    Scene scene = loadGltfFromMemory({reinterpret_cast<const uint8_t *>(json.data()), json.size()},
                                     "cubes.gltf", std::filesystem::temp_directory_path());
    worldOrigin = scene.worldOrigin;
    // Light and camera in scene space, relative to the (re-centred) bounds.
    const Bounds3f b = scene.bounds();
    Light light;
    light.position = b.center() + glm::vec3(3.f, 5.f, 4.f);
    scene.lights = {light};
    const Tracer tracer(scene);
    return test::renderWithPolicy(tracer, Camera::framing(b, 45.f, float(kWidth) / float(kHeight)), kWidth,
                                  kHeight, 1, 0);
}

/// Case 20. (a) Through the glTF loader, which re-centres in double: the image at translation T
/// up to 1e7 (with fractional parts) equals the one at T = 0. (b) A built scene translated in
/// float without re-centring: the error is measured and reported (mvcl does not re-centre scenes
/// built in code; their builder must, as the loader does).
TEST(RobustnessInvariance, LoaderRecentringMakesImagesTranslationInvariant) {
    glm::dvec3 origin0;
    const auto reference = renderLoadedCubes(glm::dvec3(0.0), origin0);
    const auto builtReference = renderInvarianceScene(1.0, glm::dvec3(0.0));
    std::string table = "translation invariance: T, loader mean |diff|, built-without-re-centring mean |diff|\n";
    double worstLoaded = 0;
    for (const double t : {1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7}) {
        const glm::dvec3 translation = t * glm::dvec3(1.0, 0.37, -0.61) + glm::dvec3(0.123, 0.456, 0.789);
        glm::dvec3 worldOrigin;
        const auto loaded = renderLoadedCubes(translation, worldOrigin);
        const double loadedDiff = test::meanAbsDifference(loaded.image, reference.image);
        worstLoaded = std::max(worstLoaded, loadedDiff);
        EXPECT_LT(loadedDiff, 1e-3) << "T=" << t;
        EXPECT_NEAR(worldOrigin.x - origin0.x, translation.x, 1e-6 * t) << "T=" << t;
        EXPECT_EQ(test::nonFinitePixels(loaded.image) + loaded.stats.rays.nonFiniteSamples, 0u);
        const auto built = renderInvarianceScene(1.0, translation);
        EXPECT_EQ(test::nonFinitePixels(built.image) + built.stats.rays.nonFiniteSamples, 0u) << "T=" << t;
        char row[96];
        std::snprintf(row, sizeof row, "  %-6.0e %.2e %.2e\n", t, loadedDiff,
                      test::meanAbsDifference(built.image, builtReference.image));
        table += row;
    }
    std::printf("%s", table.c_str());
    measured("translation invariance through the loader: worst mean |diff| = " + std::to_string(worstLoaded));
}

} // namespace
} // namespace mvcl
