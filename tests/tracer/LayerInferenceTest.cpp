#include <mvcl/tracer/LayerInference.h>

#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/Scene.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <map>
#include <string>

using namespace mvcl;

namespace {

const std::filesystem::path kModels = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";

/// A closed axis-aligned box with outward counter-clockwise triangles.
TriangleMesh box(const std::string &name, glm::vec3 centre, float half) {
    TriangleMesh m;
    m.name = name;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(centre + half * glm::vec3(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f));
    const unsigned quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &q : quads) {
        m.indices.emplace_back(q[0], q[1], q[2]);
        m.indices.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

Scene nestedBoxes() {
    Scene s;
    s.materials.push_back(Material{});
    s.meshes.push_back(box("inner", glm::vec3(0.1f), 1.f));
    s.meshes.push_back(box("outer", glm::vec3(0.f), 3.f));
    s.meshes.push_back(box("middle", glm::vec3(0.f), 2.f));
    s.meshes.push_back(box("aside", glm::vec3(20.f, 0.f, 0.f), 1.f)); // encloses nothing, enclosed by nothing
    return s;
}

std::map<std::string, int> layersByName(const Scene &s) {
    std::map<std::string, int> out;
    for (const TriangleMesh &m : s.meshes) out[m.name] = m.layer;
    return out;
}

} // namespace

TEST(LayerInference, NestedBoxesPeelOutsideIn) {
    Scene s = nestedBoxes();
    const LayerInferenceResult r = inferLayersByContainment(s);
    EXPECT_EQ(r.meshesAssigned, 4u);
    EXPECT_EQ(r.layerCount, 3);
    const auto layers = layersByName(s);
    EXPECT_EQ(layers.at("outer"), 0);
    EXPECT_EQ(layers.at("aside"), 0);
    EXPECT_EQ(layers.at("middle"), 1);
    EXPECT_EQ(layers.at("inner"), 2);
    for (const TriangleMesh &m : s.meshes) EXPECT_EQ(m.layerSource, LayerSource::Inferred);
    for (int id : {0, 1, 2}) EXPECT_NE(s.layers.find(id), nullptr);
}

TEST(LayerInference, SingleMeshAndFirstLayer) {
    Scene one;
    one.meshes.push_back(box("only", glm::vec3(0.f), 1.f));
    inferLayersByContainment(one);
    EXPECT_EQ(one.meshes[0].layer, 0);

    Scene s = nestedBoxes();
    LayerInferenceSettings settings;
    settings.firstLayer = 1;
    inferLayersByContainment(s, settings);
    const auto layers = layersByName(s);
    EXPECT_EQ(layers.at("outer"), 1);
    EXPECT_EQ(layers.at("inner"), 3);

    Scene empty;
    EXPECT_EQ(inferLayersByContainment(empty).meshesAssigned, 0u);
}

TEST(LayerInference, PresetMeshesKeepTheirLayerAndOcclude) {
    Scene s = nestedBoxes();
    for (TriangleMesh &m : s.meshes)
        if (m.name == "outer") {
            m.layer = 0;
            m.layerSource = LayerSource::Rule;
        }
    const LayerInferenceResult r = inferLayersByContainment(s);
    EXPECT_EQ(r.meshesAssigned, 3u);
    const auto layers = layersByName(s);
    EXPECT_EQ(layers.at("outer"), 0);
    EXPECT_EQ(layers.at("middle"), 1);
    EXPECT_EQ(layers.at("inner"), 2);
    for (const TriangleMesh &m : s.meshes) {
        if (m.name == "outer") {
            EXPECT_EQ(m.layerSource, LayerSource::Rule);
        }
    }
}

TEST(LayerInference, AMeshThatPokesOutButIsMostlyHiddenGoesDeeper) {
    // A rod in a long tube open at both ends (a bone seen at the joints, a valve in a heart):
    // from the rod's samples only the narrow cones toward the tube's ends are open.
    Scene s;
    s.materials.push_back(Material{});
    TriangleMesh tube = box("tube", glm::vec3(0.f), 1.f);
    tube.indices.erase(tube.indices.begin() + 8, tube.indices.end()); // drop the two x faces
    for (glm::vec3 &p : tube.positions) p *= glm::vec3(10.f, 3.f, 3.f);
    s.meshes.push_back(tube);
    TriangleMesh rod = box("rod", glm::vec3(0.f), 1.f);
    for (glm::vec3 &p : rod.positions) p *= glm::vec3(2.f, 0.3f, 0.3f);
    s.meshes.push_back(rod);
    Scene sixAxes = s;
    inferLayersByContainment(s);
    EXPECT_EQ(layersByName(s).at("tube"), 0);
    EXPECT_EQ(layersByName(s).at("rod"), 1);
    EXPECT_GT(s.meshes[0].layerConfidence, 0.5f); // nothing encloses the tube
    EXPECT_GE(s.meshes[1].layerConfidence, 0.f);
    EXPECT_LE(s.meshes[1].layerConfidence, 1.f);
    // Requiring every one of the six axis rays to be blocked (the first version of the
    // inference) calls the rod visible and puts it beside the tube.
    LayerInferenceSettings strict;
    strict.directions = 6;
    strict.hiddenFraction = 1.f;
    inferLayersByContainment(sixAxes, strict);
    EXPECT_EQ(layersByName(sixAxes).at("rod"), 0);
}

TEST(LayerInference, CoincidentShellsStillTerminate) {
    Scene s;
    s.meshes.push_back(box("a", glm::vec3(0.f), 1.f));
    s.meshes.push_back(box("b", glm::vec3(0.f), 1.f));
    inferLayersByContainment(s);
    EXPECT_EQ(s.meshes[0].layer, s.meshes[1].layer);
}

// ---------------------------------------------------------------------------------------------
// Against layers.suggested.json. The CAD/Khronos suggestions were made by the same onion-peeling
// method; the anatomy ones by a name rule (see models/README.md), so agreement there is partial:
// touching organ parts (cortex, renal columns, hilum) do not strictly enclose each other.

struct ModelCase {
    const char *folder;
    const char *file;
    /// Measured per-node agreement minus a margin. Measured (64 samples, 26 directions, hidden
    /// share 0.9, enclosed share 0.6): engine 61/67, kidney 14/15, mosquito 3/3, body 82/84, the
    /// same for 14..50 directions, hidden shares 0.9..0.95 and enclosed shares 0.6..0.7. With six
    /// axis rays all required blocked (the first version): 59/67, 14/15, 3/3, 80/84.
    double minAgreement;
};

class LayerInferenceModels : public ::testing::TestWithParam<ModelCase> {};

TEST_P(LayerInferenceModels, AgreesWithSuggestedLayers) {
    const ModelCase &c = GetParam();
    Scene s = loadGltf(kModels / c.folder / c.file);
    std::ifstream in(kModels / c.folder / "layers.suggested.json");
    const nlohmann::json suggested = nlohmann::json::parse(in);
    std::map<int, int> expected; // node → layer
    for (const auto &[layer, entries] : suggested["layers"].items())
        for (const auto &e : entries) expected[e["node"].get<int>()] = std::stoi(layer);

    const auto t0 = std::chrono::steady_clock::now();
    inferLayersByContainment(s);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    // Compare per mesh node (the loader may split a node into one TriangleMesh per material).
    std::map<int, int> inferred;
    std::map<int, std::size_t> triangles;
    for (const TriangleMesh &m : s.meshes) {
        ASSERT_TRUE(expected.count(m.sourceNode)) << "node " << m.sourceNode << " missing from the suggestions";
        const auto [it, inserted] = inferred.try_emplace(m.sourceNode, m.layer);
        EXPECT_EQ(it->second, m.layer) << "node " << m.sourceNode << " split across layers";
        triangles[m.sourceNode] += m.indices.size();
    }
    std::size_t agree = 0, total = 0, agreeTris = 0, totalTris = 0;
    for (const auto &[node, layer] : inferred) {
        ++total;
        totalTris += triangles[node];
        if (layer == expected[node]) {
            ++agree;
            agreeTris += triangles[node];
        } else {
            std::cout << "    " << c.folder << ": node " << node << " inferred " << layer << ", suggested "
                      << expected[node] << "\n";
        }
    }
    const double agreement = double(agree) / double(total);
    const double triAgreement = double(agreeTris) / double(totalTris);
    std::cout << "  " << c.folder << ": layer agreement " << 100.0 * agreement << "% of " << total << " mesh nodes ("
              << 100.0 * triAgreement << "% of triangles), inference " << ms << " ms\n";
    RecordProperty(std::string(c.folder) + "_agreement_percent", std::to_string(100.0 * agreement));
    RecordProperty(std::string(c.folder) + "_inference_ms", std::to_string(ms));
    EXPECT_GE(agreement, c.minAgreement);
}

INSTANTIATE_TEST_SUITE_P(LayerInferenceSuggested, LayerInferenceModels,
                         ::testing::Values(ModelCase{"2CylinderEngine", "2CylinderEngine.glb", 0.88},
                                           ModelCase{"HRA_Kidney_Female_Left", "VH_F_Kidney_L.glb", 0.9},
                                           ModelCase{"MosquitoInAmber", "MosquitoInAmber.glb", 1.0},
                                           ModelCase{"HRA_Female_Body", "HRA_Female_Body.glb", 0.95}),
                         [](const auto &info) { return std::string(info.param.folder); });

TEST(LayerInferenceModels, OutermostLayerIsCapsuleAndSkin) {
    Scene kidney = loadGltf(kModels / "HRA_Kidney_Female_Left/VH_F_Kidney_L.glb");
    inferLayersByContainment(kidney);
    for (const TriangleMesh &m : kidney.meshes)
        EXPECT_EQ(m.layer == 0, m.name == "VH_F_kidney_capsule_L") << m.name << " layer " << m.layer;

    Scene body = loadGltf(kModels / "HRA_Female_Body/HRA_Female_Body.glb");
    inferLayersByContainment(body);
    for (const TriangleMesh &m : body.meshes)
        EXPECT_EQ(m.layer == 0, m.name == "VH_F_skin") << m.name << " layer " << m.layer;
}
