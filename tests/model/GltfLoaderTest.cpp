#include "GltfTestWriter.h"

#include <mvcl/model/GltfLoader.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace mvcl;
using namespace mvcl::test;
using nlohmann::json;

namespace {

const std::filesystem::path kModels = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";

std::string loadError(const GltfWriter &w) {
    try {
        w.load();
    } catch (const Error &e) {
        return e.what();
    }
    return "(loaded without error)";
}

glm::vec3 faceNormal(const TriangleMesh &m, std::size_t t) {
    const glm::uvec3 i = m.indices[t];
    return glm::cross(m.positions[i.y] - m.positions[i.x], m.positions[i.z] - m.positions[i.x]);
}

// ---------------------------------------------------------------------------------------------
// EdgeCases/INDEX.tsv drives one test per file.

struct EdgeCase {
    std::string file;
    std::string expectation;
    std::string why;
};

void PrintTo(const EdgeCase &c, std::ostream *os) { *os << c.file << " (" << c.expectation << ")"; }

std::vector<EdgeCase> readEdgeCaseIndex() {
    std::vector<EdgeCase> cases;
    std::ifstream in(kModels / "EdgeCases" / "INDEX.tsv");
    std::string line;
    std::getline(in, line); // header
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::vector<std::string> cols;
        std::stringstream ss(line);
        for (std::string col; std::getline(ss, col, '\t');) cols.push_back(col);
        if (cols.size() >= 5) cases.push_back({cols[0], cols[3], cols[4]});
    }
    return cases;
}

class GltfEdgeCase : public ::testing::TestWithParam<EdgeCase> {};

/// What each file must say: a piece of the error for REJECT, of a warning for the others ("" =
/// it must load without any warning). A file missing here fails the test.
const std::map<std::string, std::string> &edgeCaseMessages() {
    static const std::map<std::string, std::string> kMessages = {
        {"assimp/BoxBadNormals/BoxBadNormals.glb", ""},
        {"assimp/BoxWithInfinites/BoxWithInfinites.glb", "position 0 is (-inf, -0.500000, 0.500000), not finite"},
        {"assimp/IncorrectVertexArrays/Cube.gltf", "bufferView 2 ends at byte 936, 422 bytes past the end of buffer 0"},
        {"assimp/IndexOutOfRange/AllIndicesOutOfRange.gltf", "is the primitive-restart value 65535"},
        {"assimp/IndexOutOfRange/IndexOutOfRange.gltf", "index 0 is 255, but the primitive has only 24 vertices"},
        {"assimp/MissingBin/BoxTextured.gltf", "File not found : BoxTextured0.bin"},
        {"assimp/RecursiveNodes/RecursiveNodes.gltf", "the node hierarchy has a cycle through node 0"},
        {"assimp/SchemaFailures/sceneWrongType.gltf", "File not found : BoxTextured0.bin"},
        {"assimp/TestNoRootNode/NoScene.gltf", "\"scene\" is 0, but the file has 0 scenes"},
        {"assimp/TestNoRootNode/SceneWithoutNodes.gltf", ""},
        {"assimp/issue_3269/texcoord_crash.gltf", ""},
        {"assimp/wrongTypes/badArray.gltf", "mesh 0 'Mesh' has no primitives"},
        {"assimp/wrongTypes/badExtension.gltf", "baseColorTexture extension KHR_texture_transform is not an object; ignored"},
        {"assimp/wrongTypes/badNumber.gltf", "normalTexture has no valid texture index; ignored"},
        {"assimp/wrongTypes/badObject.gltf", "pbrMetallicRoughness is not an object; glTF's defaults are used"},
        {"assimp/wrongTypes/badString.gltf", "scene 0 name is not a string; ignored"},
        {"assimp/wrongTypes/badUint.gltf", "baseColorTexture has no valid texture index; ignored"},
        {"tinygltf/BoundsChecking/integer-out-of-bounds.gltf", "'byteLength' property is not a positive integer"},
        {"tinygltf/BoundsChecking/invalid-buffer-index.gltf", "bufferView 1 refers to buffer 1, but the file has 1 buffers"},
        {"tinygltf/BoundsChecking/invalid-buffer-view-index.gltf", "accessor[0] invalid bufferView"},
        {"tinygltf/BoundsChecking/invalid-primitive-indices.gltf", "primitive indices accessor out of bounds"},
        {"tinygltf/issue-416.gltf", "uri '\\x00AAAQAAA5' contains a NUL byte"},
        {"tinygltf/issue-492.glb", "'inverseBindMatrices' property is missing in Skin"},
        {"tinygltf/zero-sized-bin-chunk-issue-440.glb", ""},
    };
    return kMessages;
}

bool hasWarningWith(const Scene &s, const std::string &text) {
    for (const std::string &w : s.report.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

/// Warnings other than tinygltf's own notes.
std::size_t ownWarnings(const Scene &s) {
    std::size_t n = 0;
    for (const std::string &w : s.report.warnings)
        if (w.rfind("tinygltf: ", 0) != 0) ++n;
    return n;
}

TEST_P(GltfEdgeCase, MeetsIndexExpectation) {
    const EdgeCase &c = GetParam();
    const std::filesystem::path path = kModels / "EdgeCases" / c.file;
    const std::string fileName = path.filename().string();
    SCOPED_TRACE(c.file + " expects " + c.expectation + ": " + c.why);
    const auto message = edgeCaseMessages().find(c.file);
    ASSERT_NE(message, edgeCaseMessages().end()) << c.file << " has no expected message in this test";
    const std::string &text = message->second;
    if (c.expectation == "REJECT") {
        try {
            loadGltf(path);
            FAIL() << c.file << " loaded but must be rejected";
        } catch (const Error &e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(fileName), std::string::npos) << what;
            EXPECT_NE(what.find(text), std::string::npos) << what;
            // Never raw bytes of the file: only printable ASCII and UTF-8 text.
            for (unsigned char ch : what) EXPECT_TRUE(ch >= 0x20 && ch != 0x7f) << what;
            std::cout << "  [rejected] " << what << "\n";
        }
    } else if (c.expectation == "LOAD" || c.expectation == "LOAD-WITH-WARNING") {
        Scene s;
        ASSERT_NO_THROW(s = loadGltf(path));
        if (text.empty())
            EXPECT_EQ(s.report.warnings.size(), 0u) << s.report.warnings.front();
        else
            EXPECT_TRUE(hasWarningWith(s, text)) << (s.report.warnings.empty() ? "no warnings" : s.report.warnings.front());
        if (c.expectation == "LOAD-WITH-WARNING") {
            EXPECT_GE(ownWarnings(s), 1u);
            EXPECT_GT(s.triangleCount(), 0u); // only material parts are wrong: the geometry loads
        }
    } else {
        FAIL() << "unknown expectation " << c.expectation;
    }
}

INSTANTIATE_TEST_SUITE_P(GltfIndex, GltfEdgeCase, ::testing::ValuesIn(readEdgeCaseIndex()),
                         [](const ::testing::TestParamInfo<EdgeCase> &info) {
                             std::string name = info.param.file;
                             for (char &ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

TEST(GltfEdgeCaseIndex, IsNotEmpty) { EXPECT_GE(readEdgeCaseIndex().size(), 20u); }

TEST(GltfEdgeCaseDetails, SpecificOutcomes) {
    const Scene normals = loadGltf(kModels / "EdgeCases/assimp/BoxBadNormals/BoxBadNormals.glb");
    EXPECT_GT(normals.report.nonUnitNormalsFixed, 0u);
    for (const TriangleMesh &m : normals.meshes)
        for (const glm::vec3 &n : m.normals) EXPECT_NEAR(glm::length(n), 1.f, 1e-5f);
    EXPECT_EQ(loadGltf(kModels / "EdgeCases/assimp/TestNoRootNode/SceneWithoutNodes.gltf").triangleCount(), 0u);
    EXPECT_EQ(loadGltf(kModels / "EdgeCases/tinygltf/issue-492.glb").triangleCount(), 0u);
    EXPECT_EQ(loadGltf(kModels / "EdgeCases/tinygltf/zero-sized-bin-chunk-issue-440.glb").triangleCount(), 1u);
    const auto expectMessage = [](const char *file, const char *text) {
        try {
            loadGltf(kModels / "EdgeCases" / file);
            ADD_FAILURE() << file << " loaded";
        } catch (const Error &e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
        }
    };
    expectMessage("assimp/RecursiveNodes/RecursiveNodes.gltf", "cycle");
    expectMessage("assimp/BoxWithInfinites/BoxWithInfinites.glb", "not finite");
    expectMessage("assimp/IndexOutOfRange/IndexOutOfRange.gltf", "but the primitive has only");
    expectMessage("assimp/IncorrectVertexArrays/Cube.gltf", "past the end of buffer");
    expectMessage("assimp/TestNoRootNode/NoScene.gltf", "\"scene\" is 0");
}

// ---------------------------------------------------------------------------------------------
// The seven real models against models.json.

TEST(GltfRealModels, TriangleCountsAndBoundsMatchModelsJson) {
    std::ifstream in(kModels / "models.json");
    const json models = json::parse(in);
    ASSERT_EQ(models.size(), 7u);
    for (const json &m : models) {
        const std::string name = m["name"];
        SCOPED_TRACE(name);
        const auto t0 = std::chrono::steady_clock::now();
        const Scene s = loadGltf(kModels / m["file"].get<std::string>());
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::cout << "  " << name << ": " << s.triangleCount() << " triangles, " << s.meshes.size() << " meshes, "
                  << s.report.degenerateTrianglesDropped << " degenerate dropped, loaded in " << ms << " ms\n";
        ::testing::Test::RecordProperty(name + "_load_ms", std::to_string(ms));
        EXPECT_EQ(s.triangleCount() + s.report.degenerateTrianglesDropped, m["triangles_in_scene"].get<std::size_t>());
        const Bounds3f b = s.bounds();
        const glm::dvec3 lo = glm::dvec3(b.min) + s.worldOrigin, hi = glm::dvec3(b.max) + s.worldOrigin;
        double extent = 0;
        for (int k = 0; k < 3; ++k) extent = std::max(extent, m["bbox_max"][k].get<double>() - m["bbox_min"][k].get<double>());
        // 1e-3 relative, plus 5e-5 because models.json rounds to four decimals.
        const double tol = 1e-3 * extent + 5e-5;
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(lo[k], m["bbox_min"][k].get<double>(), tol) << "axis " << k;
            EXPECT_NEAR(hi[k], m["bbox_max"][k].get<double>(), tol) << "axis " << k;
        }
        EXPECT_FALSE(s.materials.empty());
        for (const TriangleMesh &mesh : s.meshes) {
            EXPECT_GE(mesh.sourceNode, 0);
            EXPECT_GE(mesh.sourceMesh, 0);
            EXPECT_LT(mesh.material, s.materials.size());
            EXPECT_TRUE(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size());
        }
    }
}

TEST(GltfRealModels, KidneyNonUnitNormalIsFixedAndDuckCameraLoads) {
    const Scene kidney = loadGltf(kModels / "HRA_Kidney_Female_Left/VH_F_Kidney_L.glb");
    EXPECT_GE(kidney.report.nonUnitNormalsFixed, 1u);
    const Scene duck = loadGltf(kModels / "Duck/Duck.glb");
    ASSERT_EQ(duck.cameras.size(), 1u);
    EXPECT_GT(duck.cameras[0].verticalFovDegrees, 1.f);
    EXPECT_LT(duck.cameras[0].verticalFovDegrees, 179.f);
    const Scene amber = loadGltf(kModels / "MosquitoInAmber/MosquitoInAmber.glb");
    float maxTransparency = 0;
    for (const Material &m : amber.materials) maxTransparency = std::max(maxTransparency, m.transparency);
    EXPECT_GT(maxTransparency, 0.5f); // KHR_materials_transmission on the amber
}

// ---------------------------------------------------------------------------------------------
// Geometry processing.

TEST(GltfGeometry, NegativeScaleFlipsWinding) {
    GltfWriter w;
    const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int nrm = w.accessor(w.view(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}), 5126, 3, "VEC3");
    const int m = w.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}});
    w.scene({w.node({{"mesh", m}, {"scale", {-1.0, 1.0, 1.0}}}), w.node({{"mesh", m}, {"translation", {5.0, 0.0, 0.0}}})});
    const Scene s = w.load();
    ASSERT_EQ(s.meshes.size(), 2u);
    for (const TriangleMesh &mesh : s.meshes) {
        const glm::vec3 n = faceNormal(mesh, 0);
        EXPECT_GT(n.z, 0.f);                        // still counter-clockwise from +Z
        EXPECT_GT(glm::dot(n, mesh.normals[0]), 0.f); // and agreeing with the shading normal
    }
}

TEST(GltfGeometry, ZeroScaleInstanceDroppedWithWarning) {
    GltfWriter w = triangleFile();
    w.doc["nodes"][0]["scale"] = {0.0, 1.0, 1.0};
    const Scene s = w.load();
    EXPECT_EQ(s.triangleCount(), 0u);
    EXPECT_FALSE(s.report.warnings.empty());
}

TEST(GltfGeometry, NormalsNormalisedZeroNormalsAndDegenerateTriangles) {
    GltfWriter w;
    const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0});
    const int nrm = w.accessor(w.view(std::vector<float>{0, 0, 2, 0, 0, 0, 0, 0, 1, 0, 0, 1}), 5126, 4, "VEC3");
    const int idx = w.indices16({0, 1, 2, 0, 1, 3, 2, 2, 1});
    w.scene({w.node({{"mesh", w.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}})}})});
    const Scene s = w.load();
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_EQ(s.report.degenerateTrianglesDropped, 2u); // collinear, and a repeated vertex
    EXPECT_EQ(s.report.nonUnitNormalsFixed, 2u);          // length 2, and a zero normal
    const TriangleMesh &m = s.meshes[0];
    for (const glm::vec3 &n : m.normals) EXPECT_NEAR(glm::length(n), 1.f, 1e-6f);
    EXPECT_NEAR(m.normals[1].z, 1.f, 1e-6f); // the zero normal took the face normal
}

TEST(GltfGeometry, RecentredInDoubleFarFromOrigin) {
    GltfWriter w = triangleFile();
    w.doc["nodes"][0]["translation"] = {1e7, -3e6, 0.25};
    const Scene s = w.load();
    EXPECT_NEAR(s.worldOrigin.x, 1e7 + 0.5, 1e-9);
    EXPECT_NEAR(s.worldOrigin.y, -3e6 + 0.5, 1e-9);
    // Scene-space positions keep full precision: the triangle is exactly ±0.5 around the origin.
    EXPECT_EQ(s.meshes[0].positions[1].x, 0.5f);
    EXPECT_EQ(s.meshes[0].positions[2].y, 0.5f);
}

// ---------------------------------------------------------------------------------------------
// Layers, materials, lights, cameras, scenes.

TEST(GltfLayers, ExtrasThenRulesThenUnassigned) {
    GltfWriter w;
    const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int plain = w.mesh({{"attributes", {{"POSITION", pos}}}}, "plainMesh");
    const int tagged = w.mesh({{"attributes", {{"POSITION", pos}}}}, "taggedMesh");
    w.doc["meshes"][tagged]["extras"] = {{"layer", 3}};
    w.scene({w.node({{"mesh", plain}, {"name", "a"}, {"extras", {{"layer", 2}}}}),
             w.node({{"mesh", tagged}, {"name", "b"}}),
             w.node({{"mesh", tagged}, {"name", "c"}, {"extras", {{"layer", 1}}}}),
             w.node({{"mesh", plain}, {"name", "skinNode"}}),
             w.node({{"mesh", plain}, {"name", "d"}})});
    GltfLoadOptions options;
    options.layerRules = LayerRules::fromString("*skin*=5");
    const Scene s = w.load(options);
    ASSERT_EQ(s.meshes.size(), 5u);
    EXPECT_EQ(s.meshes[0].layer, 2);
    EXPECT_EQ(s.meshes[0].layerSource, LayerSource::Extras);
    EXPECT_EQ(s.meshes[1].layer, 3); // mesh extras
    EXPECT_EQ(s.meshes[1].layerSource, LayerSource::Extras);
    EXPECT_EQ(s.meshes[2].layer, 1); // node extras win over mesh extras
    EXPECT_EQ(s.meshes[3].layer, 5);
    EXPECT_EQ(s.meshes[3].layerSource, LayerSource::Rule);
    EXPECT_EQ(s.meshes[4].layerSource, LayerSource::Unassigned);
    EXPECT_EQ(s.meshes[4].name, "d");
    EXPECT_EQ(s.meshes[4].meshName, "plainMesh");
    EXPECT_EQ(s.meshes[4].sourceNode, 4);
    for (int id : {1, 2, 3, 5}) EXPECT_NE(s.layers.find(id), nullptr) << id;

    w.doc["nodes"][0]["extras"]["layer"] = 40;
    EXPECT_NE(loadError(w).find("extras.layer"), std::string::npos) << loadError(w);
    w.doc["nodes"][0]["extras"]["layer"] = "outer";
    EXPECT_NE(loadError(w).find("extras.layer"), std::string::npos) << loadError(w);
}

TEST(GltfNames, NodeNameKeptAsWrittenBesideTheDisplayName) {
    GltfWriter w;
    const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int named = w.mesh({{"attributes", {{"POSITION", pos}}}}, "organMesh");
    const int anonymous = w.mesh({{"attributes", {{"POSITION", pos}}}});
    w.scene({w.node({{"mesh", named}, {"name", "kidneyNode"}}), w.node({{"mesh", named}}),
             w.node({{"mesh", anonymous}})});
    const Scene s = w.load();
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_EQ(s.meshes[0].nodeName, "kidneyNode");
    EXPECT_EQ(s.meshes[0].name, "kidneyNode");
    EXPECT_EQ(s.meshes[1].nodeName, "") << "a node without a name stays without one";
    EXPECT_EQ(s.meshes[1].name, "organMesh") << "the display name falls back to the mesh name";
    EXPECT_EQ(s.meshes[2].nodeName, "");
    EXPECT_EQ(s.meshes[2].name, "node 2");
}

TEST(GltfMaterials, PbrMappedToPhongAndDefaultMaterial) {
    GltfWriter w;
    const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    w.doc["materials"] = json::array(
        {{{"name", "redPlastic"},
          {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.0, 0.0, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}}},
         {{"name", "chrome"}, {"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}},
         {{"name", "glass"},
          {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}}, {"KHR_materials_ior", {{"ior", 1.33}}}}}},
         {{"name", "fade"}, {"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 0.25}}}}}});
    json mesh = {{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"material", 0}}, {{"attributes", {{"POSITION", pos}}}}}}};
    w.doc["meshes"].push_back(mesh);
    w.scene({w.node({{"mesh", 0}})});
    const Scene s = w.load();
    ASSERT_EQ(s.materials.size(), 5u); // four + the default
    const Material &red = s.materials[0];
    EXPECT_FLOAT_EQ(red.diffuse.r, 1.f);
    EXPECT_FLOAT_EQ(red.diffuse.g, 0.f);
    EXPECT_EQ(red.reflectivity, 0.f);
    EXPECT_NEAR(red.shininess, 30.f, 1e-3f); // 2/0.5⁴ − 2
    const Material &chrome = s.materials[1];
    EXPECT_FLOAT_EQ(chrome.diffuse.r, 0.f);
    EXPECT_FLOAT_EQ(chrome.reflectivity, 1.f);
    EXPECT_FLOAT_EQ(chrome.shininess, 1024.f);
    EXPECT_NEAR(s.materials[2].transparency, 0.9f, 1e-6f);
    EXPECT_NEAR(s.materials[2].ior, 1.33f, 1e-6f);
    EXPECT_NEAR(s.materials[3].transparency, 0.75f, 1e-6f);
    EXPECT_EQ(s.materials[4].name, "default");
    ASSERT_EQ(s.meshes.size(), 2u); // one per material
    EXPECT_EQ(s.meshes[1].material, 4u);

    EXPECT_EQ(GltfWriter{}.load().materials.size(), 1u); // an empty file still has a material
}

TEST(GltfLightsAndCameras, MappedToSceneSpace) {
    GltfWriter w = triangleFile();
    w.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    w.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
        {{{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 4.0}, {"name", "bulb"}},
         {{"type", "directional"}, {"name", "sun"}},
         {{"type", "spot"}, {"name", "spot"}, {"spot", {{"outerConeAngle", 0.5}}}}});
    w.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}});
    w.node({{"translation", {10.0, 0.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    w.node({{"rotation", {-0.7071067811865476, 0.0, 0.0, 0.7071067811865476}}, // −90° about X: −Z → −Y
            {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    w.node({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    w.node({{"camera", 0}, {"translation", {0.0, 0.0, 5.0}}});
    w.scene({0, 1, 2, 3, 4});
    const Scene s = w.load();
    ASSERT_EQ(s.lights.size(), 3u);
    const glm::dvec3 bulb = glm::dvec3(s.lights[0].position) + s.worldOrigin;
    EXPECT_NEAR(bulb.x, 10.0, 1e-6);
    EXPECT_EQ(s.lights[0].type, LightType::Point);
    EXPECT_FLOAT_EQ(s.lights[0].intensity.g, 2.f);
    EXPECT_FLOAT_EQ(s.lights[0].quadraticAttenuation, 1.f);
    EXPECT_EQ(s.lights[1].type, LightType::Directional);
    EXPECT_NEAR(s.lights[1].direction.y, -1.f, 1e-6f);
    EXPECT_EQ(s.lights[2].type, LightType::Point); // spot → point, with a warning
    ASSERT_EQ(s.cameras.size(), 1u);
    const CameraDesc &c = s.cameras[0];
    EXPECT_NEAR(c.verticalFovDegrees, 0.5f * 180.f / 3.14159265f, 1e-4f);
    EXPECT_NEAR(double(c.eye.z) + s.worldOrigin.z, 5.0, 1e-6);
    EXPECT_NEAR(c.target.z - c.eye.z, -1.f, 1e-6f);
    EXPECT_NEAR(c.up.y, 1.f, 1e-6f);
}

TEST(GltfScenes, DefaultSceneSelection) {
    GltfWriter w = triangleFile();
    w.node({{"mesh", 0}, {"translation", {3.0, 0.0, 0.0}}});
    w.doc["scenes"] = json::array({{{"nodes", {0}}}, {{"nodes", {1}}}});
    w.doc.erase("scene"); // no "scene": scenes[0]
    EXPECT_EQ(w.load().meshes.at(0).sourceNode, 0);
    w.doc["scene"] = 1;
    EXPECT_EQ(w.load().meshes.at(0).sourceNode, 1);
    w.doc["scene"] = 2;
    EXPECT_NE(loadError(w).find("\"scene\" is 2"), std::string::npos);
    w.doc.erase("scene");
    w.doc.erase("scenes"); // no scenes: every root node
    EXPECT_EQ(w.load().meshes.size(), 2u);
}

} // namespace
