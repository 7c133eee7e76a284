#include "MeshFileWriter.h"

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/MeshFileLoader.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <span>
#include <tuple>
#include <string>

using namespace mvcl;
using namespace mvcl::test;
namespace fs = std::filesystem;

namespace {

/// A folder of its own per test, removed afterwards.
class MeshFiles : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = fs::temp_directory_path() /
                ("mvcl-mesh-files-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    std::string write(const std::string &name, const std::string &bytes) {
        writeFile(m_dir / name, bytes);
        return (m_dir / name).string();
    }

    fs::path m_dir;
};

std::string errorOf(const auto &fn) {
    try {
        fn();
    } catch (const Error &e) {
        return e.what();
    }
    return "(no error)";
}

/// World-space corners of every triangle, as a sorted list: equal for two loads of the same
/// geometry whatever their vertex numbering.
std::multiset<std::tuple<float, float, float>> worldCorners(const Scene &scene) {
    std::multiset<std::tuple<float, float, float>> corners;
    for (const TriangleMesh &m : scene.meshes)
        for (const glm::uvec3 &t : m.indices)
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 p = glm::dvec3(m.positions[t[k]]) + scene.worldOrigin;
                corners.emplace(float(p.x), float(p.y), float(p.z));
            }
    return corners;
}

/// World-space corners of every triangle in the order the file holds them.
std::vector<glm::dvec3> cornersInOrder(const Scene &scene) {
    std::vector<glm::dvec3> corners;
    for (const TriangleMesh &m : scene.meshes)
        for (const glm::uvec3 &t : m.indices)
            for (int k = 0; k < 3; ++k) corners.push_back(glm::dvec3(m.positions[t[k]]) + scene.worldOrigin);
    return corners;
}

} // namespace

TEST_F(MeshFiles, EveryFormatReadsTheSameClosedCube) {
    const PlainMesh cube = cubeMesh(glm::vec3(1.f, 2.f, 3.f));
    const std::vector<std::string> files = {
        write("cube-binary.stl", binaryStl(cube)),          write("cube-ascii.stl", asciiStl(cube)),
        write("cube-ascii.ply", ply(cube, PlyEncoding::Ascii)), write("cube-le.ply", ply(cube, PlyEncoding::LittleEndian)),
        write("cube-be.ply", ply(cube, PlyEncoding::BigEndian)), write("cube.obj", obj(cube))};
    const Scene reference = loadScene(files.front());
    for (const std::string &file : files) {
        SCOPED_TRACE(file);
        const Scene scene = loadScene(file);
        ASSERT_EQ(scene.meshes.size(), 1u);
        EXPECT_EQ(scene.meshes[0].indices.size(), 12u);
        EXPECT_EQ(scene.meshes[0].positions.size(), 8u); // STL corners welded into 8 vertices
        EXPECT_EQ(scene.meshes[0].closure, MeshClosure::Outward);
        EXPECT_EQ(worldCorners(scene), worldCorners(reference));
        EXPECT_NEAR(scene.worldOrigin.y, 2.5, 1e-9);
    }
}

TEST_F(MeshFiles, RoundTripAgainstTheGltfLoader) {
    // The same triangles written from what the glTF loader read come back in the same places.
    const Scene gltf = loadGltf(fs::path(MVCL_TEST_DATA_DIR) / "models/Duck/Duck.glb");
    PlainMesh mesh;
    for (const TriangleMesh &m : gltf.meshes) {
        const auto base = std::uint32_t(mesh.positions.size());
        for (const glm::vec3 &p : m.positions) mesh.positions.push_back(glm::vec3(glm::dvec3(p) + gltf.worldOrigin));
        for (const glm::uvec3 &t : m.indices) mesh.triangles.push_back(t + glm::uvec3(base));
    }
    for (const std::string &file : {write("duck.stl", binaryStl(mesh)), write("duck.ply", ply(mesh, PlyEncoding::BigEndian)),
                                    write("duck.obj", obj(mesh))}) {
        SCOPED_TRACE(file);
        const Scene scene = loadScene(file);
        EXPECT_EQ(scene.triangleCount(), gltf.triangleCount());
        // Float positions re-centred on another origin round differently by an ulp or so.
        const std::vector<glm::dvec3> expected = cornersInOrder(gltf), read = cornersInOrder(scene);
        ASSERT_EQ(read.size(), expected.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < read.size(); ++i) worst = std::max(worst, glm::length(read[i] - expected[i]));
        EXPECT_LT(worst, 1e-6);
        const Bounds3f a = gltf.bounds(), b = scene.bounds();
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(a.min[k] + gltf.worldOrigin[k], b.min[k] + scene.worldOrigin[k], 1e-6);
            EXPECT_NEAR(a.max[k] + gltf.worldOrigin[k], b.max[k] + scene.worldOrigin[k], 1e-6);
        }
    }
}

TEST_F(MeshFiles, PlyNormalsAndColoursAreRead) {
    PlainMesh cube = cubeMesh();
    for (const glm::vec3 &p : cube.positions) {
        cube.normals.push_back(glm::vec3(2.f) * (p - glm::vec3(0.5f))); // not unit: normalised on load
        cube.colors.push_back(glm::vec3(1.f, 0.f, 0.f));
    }
    const Scene scene = loadScene(write("coloured.ply", ply(cube, PlyEncoding::LittleEndian)));
    ASSERT_EQ(scene.meshes[0].normals.size(), 8u);
    EXPECT_NEAR(glm::length(scene.meshes[0].normals[0]), 1.f, 1e-6f);
    EXPECT_GT(scene.report.nonUnitNormalsFixed, 0u);
    const Material &m = scene.materials[scene.meshes[0].material];
    EXPECT_FLOAT_EQ(m.diffuse.r, 1.f);
    EXPECT_FLOAT_EQ(m.diffuse.g, 0.f);
}

TEST_F(MeshFiles, ObjGroupsBecomeNamedMeshesAndMtlColoursMaterials) {
    write("parts.mtl", "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 20\nnewmtl blue\nKd 0 0 1\n");
    const PlainMesh a = cubeMesh(), b = cubeMesh(glm::vec3(0.25f), 0.5f);
    std::string text = "mtllib parts.mtl\n";
    for (const glm::vec3 &p : a.positions) text += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    for (const glm::vec3 &p : b.positions) text += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    text += "g housing\nusemtl red\n";
    for (const glm::uvec3 &t : a.triangles) text += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    text += "o gear\nusemtl blue\n";
    for (const glm::uvec3 &t : b.triangles) text += "f " + std::to_string(t.x + 9) + " " + std::to_string(t.y + 9) + " " + std::to_string(t.z + 9) + "\n";
    const Scene scene = loadScene(write("parts.obj", text));
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[0].name, "housing");
    EXPECT_EQ(scene.meshes[1].name, "gear");
    EXPECT_EQ(scene.materials[scene.meshes[0].material].name, "red");
    EXPECT_FLOAT_EQ(scene.materials[scene.meshes[0].material].diffuse.r, 1.f);
    EXPECT_FLOAT_EQ(scene.materials[scene.meshes[1].material].diffuse.b, 1.f);
    EXPECT_FLOAT_EQ(scene.materials[scene.meshes[0].material].specular, 0.5f);
    // Inference puts the gear inside the housing.
    EXPECT_EQ(scene.meshes[0].layer, 0);
    EXPECT_EQ(scene.meshes[1].layer, 1);
}

TEST_F(MeshFiles, UpAxisAndUnitAreAppliedOrRecordedAsAssumed) {
    const std::string file = write("z-up-mm.stl", binaryStl(cubeMesh(glm::vec3(0.f), 10.f)));
    const Scene assumed = loadScene(file);
    EXPECT_EQ(assumed.report.assumptions, (std::vector<std::string>{"y up", "unit m"}));
    EXPECT_NEAR(assumed.bounds().extent().x, 10.f, 1e-5f);
    SceneLoadOptions options;
    options.upAxis = UpAxis::Z;
    options.unit = LengthUnit::Millimetre;
    const Scene told = loadScene(file, options);
    EXPECT_TRUE(told.report.assumptions.empty());
    EXPECT_NEAR(told.bounds().extent().x, 0.01f, 1e-7f);
    // z up: the file's z becomes y, the file's y becomes −z.
    EXPECT_NEAR(told.worldOrigin.y, 0.005, 1e-9);
    EXPECT_NEAR(told.worldOrigin.z, -0.005, 1e-9);
}

TEST_F(MeshFiles, SeveralFilesAreLayersNamedAfterThem) {
    const std::vector<std::string> files = {write("skin.stl", binaryStl(cubeMesh(glm::vec3(0.f), 4.f))),
                                            write("skeleton.ply", ply(cubeMesh(glm::vec3(1.f), 2.f), PlyEncoding::Ascii))};
    const Scene scene = loadScene(std::span(files));
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[0].layer, 0);
    EXPECT_EQ(scene.meshes[1].layer, 1);
    EXPECT_EQ(scene.meshes[1].layerSource, LayerSource::File);
    EXPECT_EQ(scene.layers.find(0)->name, "skin");
    EXPECT_EQ(scene.layers.find(1)->name, "skeleton");
    // One world: the inner cube stays centred in the outer one.
    EXPECT_NEAR(scene.worldOrigin.x, 2.0, 1e-9);
    const Bounds3f inner = [&] {
        Bounds3f b;
        for (const glm::vec3 &p : scene.meshes[1].positions) b.expand(p);
        return b;
    }();
    EXPECT_NEAR(inner.min.x, -1.f, 1e-6f);
    EXPECT_NEAR(inner.max.x, 1.f, 1e-6f);

    // A rule places and names a layer over the files' order.
    SceneLoadOptions options;
    options.layerRules = LayerRules::fromString("skeleton=2:bones");
    const Scene ruled = loadScene(std::span(files), options);
    EXPECT_EQ(ruled.meshes[1].layer, 2);
    EXPECT_EQ(ruled.layers.find(2)->name, "bones");
    EXPECT_EQ(ruled.layers.find(0)->name, "skin");
    EXPECT_EQ(describeSources(files), files[0] + " + " + files[1]);
}

TEST(LayerNames, GltfLayersTakeTheCommonPrefixOfTheirNodeNames) {
    const Scene kidney = loadScene((fs::path(MVCL_TEST_DATA_DIR) / "models/HRA_Kidney_Female_Left/VH_F_Kidney_L.glb").string());
    EXPECT_EQ(kidney.layers.find(0)->name, "VH_F_kidney_capsule_L");
    // Every node name starts with "VH_F": that prefix names no layer but one holding every mesh.
    for (const Layer &layer : kidney.layers.layers()) EXPECT_NE(layer.name, "VH_F");
    const Scene box = loadScene((fs::path(MVCL_TEST_DATA_DIR) / "models/Box/Box.glb").string());
    EXPECT_EQ(box.layers.find(0)->name, "Mesh"); // no node name: the mesh's name
}

TEST_F(MeshFiles, BadFilesGiveOneLineNamingTheFile) {
    const std::string cube = binaryStl(cubeMesh());
    const std::string plyText = ply(cubeMesh(), PlyEncoding::Ascii);
    struct Case {
        std::string name, bytes, expected;
    };
    const Case cases[] = {
        {"truncated.stl", cube.substr(0, cube.size() - 7), "binary STL header says 12 triangles"},
        {"empty.stl", "", "the file is empty"},
        {"lying.ply", std::string(plyText).replace(plyText.find("element vertex 8"), 16, "element vertex 9"),
         "vertex 8 has more values than the header declares"},
        {"short.ply", std::string(plyText).replace(plyText.find("element face 12"), 15, "element face 13"),
         "the header says 13 faces but the file ends after 12"},
        {"lying-binary.ply",
         [] {
             std::string b = ply(cubeMesh(), PlyEncoding::LittleEndian);
             return b.replace(b.find("element face 12"), 15, "element face 99");
         }(),
         "the header says 99 faces"},
        {"out-of-range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "refers to vertex 7, but the file has 3 vertices"},
        {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "not finite"},
        {"nan.ply", std::string(plyText).replace(plyText.find("end_header\n") + 11, 1, "nan"), "not finite"},
        {"nan.stl", asciiStl(cubeMesh()).replace(asciiStl(cubeMesh()).find("vertex ") + 7, 1, "nan"), "not finite"},
        {"image.stl", "\x89PNG\r\n\x1a\n" + std::string(200, 'x'), "a PNG image, not a model"},
        {"points.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n", "no faces"},
        {"garbage.obj", "hello world\n", "holds no faces"},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.name);
        const std::string path = write(c.name, c.bytes);
        const std::string error = errorOf([&] { loadScene(path); });
        EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
}

/// The OBJ reader checks every number of v, vn and vt lines itself (tinyobjloader reads what it
/// cannot parse as 0): a fast syntax check for plain decimals, std::from_chars for the rest.
TEST_F(MeshFiles, ObjCoordinatesAreCheckedInEverySpelling) {
    const std::string good = "v +1.5 .5 5.\nv 1e5 -0 1E-05\n  v\t0 1 0 # a comment\nvn 0 0 1\nvt 0.25 1e+2\n"
                             "v 123456789012345678901234567890 0 1e-99\nf 1 2 3\nf 1 2 4\n";
    const Scene scene = loadScene(write("spellings.obj", good));
    EXPECT_EQ(scene.triangleCount(), 2u);
    const struct {
        const char *coordinate, *expected;
    } bad[] = {
        {"1e999", "'1e999' is not finite"},    {"-inf", "'-inf' is not finite"},  {"nan", "'nan' is not finite"},
        {"1e-400", "'1e-400' is not finite"},  {"1.2.3", "'1.2.3' is not a number"}, {"1e", "'1e' is not a number"},
        {"0x10", "'0x10' is not a number"},    {"--1", "'--1' is not a number"},  {".", "'.' is not a number"},
    };
    for (const auto &c : bad) {
        SCOPED_TRACE(c.coordinate);
        const std::string path = write("bad-number.obj", std::string("v 0 0 0\nv 1 0 0\nvn 0 ") + c.coordinate + " 1\nv 0 1 0\nf 1 2 3\n");
        const std::string error = errorOf([&] { loadScene(path); });
        EXPECT_NE(error.find("line 3: vn coordinate " + std::string(c.expected)), std::string::npos) << error;
    }
}

/// What tinyobjloader's two interfaces must agree on: the callback one (files without vertex
/// colours) and LoadObj (with them).
TEST_F(MeshFiles, ObjGroupsObjectsRelativeIndicesAndVertexColoursReadAlike) {
    const std::string body = "f -3 -2 -1\ng left side\nf 1 2 3\nusemtl nowhere\nf 1 3 4\no thing\nf 2 3 4\nl 1 2\n";
    const std::string plain = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n" + body;
    const std::string coloured = "v 0 0 0 1 0 0\nv 1 0 0 1 0 0\nv 0 1 0 1 0 0\nv 0 0 1 1 0 0\n" + body;
    for (const bool hasColours : {false, true}) {
        const std::string &text = hasColours ? coloured : plain;
        SCOPED_TRACE(hasColours ? "vertex colours (LoadObj)" : "no colours (callbacks)");
        const Scene scene = loadScene(write(hasColours ? "coloured.obj" : "plain.obj", text));
        // A material missing from the library is no material: the group stays one mesh.
        ASSERT_EQ(scene.meshes.size(), 3u);
        EXPECT_EQ(scene.meshes[0].name, hasColours ? "coloured" : "plain") << "faces before any group: the file's stem";
        EXPECT_EQ(scene.meshes[0].indices[0], glm::uvec3(0, 1, 2)) << "f -3 -2 -1 after 4 vertices";
        EXPECT_EQ(scene.meshes[1].name, "left side") << "a g line's names, joined";
        EXPECT_EQ(scene.meshes[1].indices.size(), 2u);
        EXPECT_EQ(scene.meshes[2].name, "thing");
        EXPECT_NE(scene.meshes[1].sourceNode, scene.meshes[2].sourceNode);
        EXPECT_EQ(scene.triangleCount(), 4u);
        const auto warned = [&](const std::string &what) {
            return std::any_of(scene.report.warnings.begin(), scene.report.warnings.end(),
                               [&](const std::string &w) { return w.find(what) != std::string::npos; });
        };
        EXPECT_TRUE(warned("'nowhere' ] not found"));
        EXPECT_TRUE(warned("lines and points are skipped"));
        EXPECT_EQ(warned("vertex colours are averaged"), hasColours);
    }
    const std::string zero = errorOf([&] { loadScene(write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")); });
    EXPECT_NE(zero.find("zero.obj: "), std::string::npos) << zero;
    EXPECT_NE(zero.find("index 0"), std::string::npos) << zero;
}

TEST_F(MeshFiles, MisleadingExtensionIsReadByContentWithAWarning) {
    const Scene scene = loadScene(write("really-a-ply.stl", ply(cubeMesh(), PlyEncoding::BigEndian)));
    EXPECT_EQ(scene.triangleCount(), 12u);
    EXPECT_TRUE(std::any_of(scene.report.warnings.begin(), scene.report.warnings.end(), [](const std::string &w) {
        return w.find("named .stl but holds PLY") != std::string::npos;
    }));
}

TEST(MeshFilesByOtherTools, CgalSamplesLoad) {
    const fs::path dir = fs::path(MVCL_TEST_DATA_DIR) / "meshes/cgal";
    const Scene stl = loadScene((dir / "sphere.stl").string());
    EXPECT_EQ(stl.triangleCount(), 320u);
    EXPECT_EQ(stl.meshes[0].closure, MeshClosure::Outward);
    const Scene plyScene = loadScene((dir / "sphere.ply").string());
    EXPECT_EQ(plyScene.triangleCount(), 320u);
    EXPECT_EQ(plyScene.meshes[0].positions.size(), 162u);
    const Scene tetra = loadScene((dir / "colored_tetra.ply").string());
    EXPECT_EQ(tetra.triangleCount(), 4u);
    EXPECT_EQ(tetra.meshes[0].normals.size(), 4u);
    EXPECT_NE(tetra.materials[tetra.meshes[0].material].name.find("vertex colours"), std::string::npos);
    // Its extra element (edges with a confidence) is skipped with a warning, not an error.
    EXPECT_TRUE(std::any_of(tetra.report.warnings.begin(), tetra.report.warnings.end(),
                            [](const std::string &w) { return w.find("not read") != std::string::npos; }));
}

TEST(MeshFilesByOtherTools, AssimpObjSamplesLoadWithTheirGroupsAndMaterials) {
    const fs::path dir = fs::path(MVCL_TEST_DATA_DIR) / "meshes/assimp";
    // MilkShape 3D's export: a mesh per group, its material from the library.
    const Scene spider = loadScene((dir / "spider.obj").string());
    ASSERT_EQ(spider.meshes.size(), 19u);
    EXPECT_EQ(spider.triangleCount() + spider.report.degenerateTrianglesDropped, 1368u);
    EXPECT_EQ(spider.report.degenerateTrianglesDropped, 56u);
    const std::vector<std::string> groups = {"HLeib01", "OK", "Bein1Li", "Bein1Re", "Bein2Li", "Bein2Re", "Bein3Re",
                                             "Bein3Li", "Bein4Re", "Bein4Li", "Zahn", "klZahn", "Kopf", "Brust",
                                             "Kopf2", "Zahn2", "klZahn2", "Auge", "Duplicate05"};
    const std::vector<std::string> materialOfGroup = {"HLeibTex", "Skin", "BeinTex", "BeinTex", "BeinTex", "BeinTex",
                                                      "BeinTex", "BeinTex", "BeinTex", "BeinTex", "BeinTex", "BeinTex",
                                                      "Skin", "Skin", "Skin", "BeinTex", "BeinTex", "Augentex", "Augentex"};
    for (std::size_t i = 0; i < groups.size(); ++i) {
        SCOPED_TRACE(groups[i]);
        EXPECT_EQ(spider.meshes[i].name, groups[i]);
        EXPECT_EQ(spider.materials[spider.meshes[i].material].name, materialOfGroup[i]);
    }
    EXPECT_EQ(spider.meshes[0].indices.size(), 80u);
    EXPECT_EQ(spider.meshes[0].closure, MeshClosure::Outward) << "the abdomen is a closed solid";
    EXPECT_EQ(spider.meshes[2].normals.size(), spider.meshes[2].positions.size()) << "its vn are read";
    const auto skin = std::find_if(spider.materials.begin(), spider.materials.end(),
                                   [](const Material &m) { return m.name == "Skin"; });
    ASSERT_NE(skin, spider.materials.end());
    EXPECT_NEAR(skin->diffuse.r, 0.827451f, 1e-6f);
    EXPECT_NEAR(skin->diffuse.b, 0.772549f, 1e-6f);

    // One group in three materials (one missing from the library): three meshes that bound one
    // solid together, so clip volumes cap the cube.
    const Scene cube = loadScene((dir / "cube_usemtl.obj").string());
    ASSERT_EQ(cube.meshes.size(), 3u);
    EXPECT_EQ(cube.triangleCount(), 12u);
    std::vector<std::string> materials;
    for (const TriangleMesh &m : cube.meshes) {
        EXPECT_EQ(m.name, "cube");
        EXPECT_EQ(m.closure, MeshClosure::Outward) << cube.materials[m.material].name;
        materials.push_back(cube.materials[m.material].name);
    }
    EXPECT_EQ(materials, (std::vector<std::string>{"default", "mtl", "mtl2"}));
    EXPECT_TRUE(std::any_of(cube.report.warnings.begin(), cube.report.warnings.end(),
                            [](const std::string &w) { return w.find("'mtl3' ] not found") != std::string::npos; }));
    // The same file twice as layers: each file's group is a solid of its own.
    const std::vector<std::string> twice = {(dir / "cube_usemtl.obj").string(), (dir / "cube_usemtl.obj").string()};
    const Scene layered = loadScene(std::span<const std::string>(twice));
    ASSERT_EQ(layered.meshes.size(), 6u);
    EXPECT_EQ(layered.meshes[0].sourceNode, layered.meshes[2].sourceNode);
    EXPECT_NE(layered.meshes[0].sourceNode, layered.meshes[3].sourceNode);
}

TEST(LayerRuleNames, FromTextAndJson) {
    const LayerRules text = LayerRules::fromString("*skin*=0:skin; *bone*=1");
    ASSERT_EQ(text.rules().size(), 2u);
    EXPECT_EQ(text.rules()[0].name, "skin");
    EXPECT_EQ(text.rules()[1].name, "");
    const LayerRules json = LayerRules::fromJsonText(R"({"rules": [{"match": "*skin*", "layer": 0, "name": "skin"}]})", "r.json");
    EXPECT_EQ(json.rules()[0].name, "skin");
    EXPECT_THROW(LayerRules::fromJsonText(R"({"rules": [{"match": "a", "layer": 0, "name": 3}]})", "r.json"), Error);
    LayerTable layers;
    layers.ensure(0);
    text.nameLayers(layers);
    EXPECT_EQ(layers.find(0)->name, "skin");
    EXPECT_EQ(layers.find(1), nullptr); // a rule names only layers that exist
}

TEST(MeshFileSeeds, EverySeedLoads) {
    const fs::path dir = fs::path(MVCL_TEST_DATA_DIR) / "meshes/seeds";
    const Scene le = loadScene((dir / "cube-le.ply").string());
    const Scene be = loadScene((dir / "cube-be.ply").string());
    EXPECT_EQ(le.triangleCount(), 12u); // six quads, split into fans
    EXPECT_EQ(worldCorners(le), worldCorners(be));
    EXPECT_EQ(le.meshes[0].normals.size(), 8u);
    EXPECT_EQ(le.meshes[0].closure, MeshClosure::Outward);
    EXPECT_EQ(loadScene((dir / "cube-ascii.stl").string()).meshes[0].name, "cube");
    const Scene obj = loadScene((dir / "cube.obj").string());
    ASSERT_EQ(obj.meshes.size(), 3u);
    EXPECT_EQ(obj.meshes[0].name, "bottom");
    EXPECT_EQ(obj.meshes[0].normals.size(), obj.meshes[0].positions.size());
    EXPECT_EQ(obj.meshes[1].name, "top");
    EXPECT_FLOAT_EQ(obj.materials[obj.meshes[1].material].transparency, 0.5f);
    EXPECT_EQ(obj.meshes[2].name, "sides");
    EXPECT_EQ(obj.meshes[2].indices.size(), 8u);
    EXPECT_EQ(obj.triangleCount(), 12u);
}

TEST_F(MeshFiles, ObjMaterialLibrariesOutsideTheFolderAreNotRead) {
    const std::string file = write("escape.obj", "mtllib ../../etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const Scene scene = loadScene(file);
    EXPECT_TRUE(std::any_of(scene.report.warnings.begin(), scene.report.warnings.end(), [](const std::string &w) {
        return w.find("only files beside the OBJ file are read") != std::string::npos;
    }));
}

TEST_F(MeshFiles, PlyElementsWithoutPropertiesHoldNothing) {
    // A binary element of no properties takes no bytes: 10¹² of them must not be a loop of 10¹².
    std::string text = ply(cubeMesh(), PlyEncoding::LittleEndian);
    text.insert(text.find("element face"), "element nothing 1000000000000\n");
    const Scene scene = loadScene(write("empty-elements.ply", text));
    EXPECT_EQ(scene.triangleCount(), 12u);
}
