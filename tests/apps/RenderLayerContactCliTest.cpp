// mvcl-render and the contact tolerance of touching layers: --layer-contact, the session file's
// "layerContact", and --info's suggestion for near-coincident layers.

#include "RenderCliRunner.h"

#include "model/GltfTestWriter.h"
#include "tracer/TracerTestUtil.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

namespace mvcl {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;
using test::GltfWriter;
using test::outDir;
using test::quoted;
using test::runRender;

/// Two touching spheres of radius 1 with different tessellations (outer 24 × 48 on layer 0,
/// inner 32 × 64 on layer 1), 10⁷ from the origin, as a .gltf file in the scratch folder, named
/// after the running test: ctest runs the tests of this file in parallel processes, and one
/// rewriting a shared file while another renders it failed now and then.
std::string touchingSpheresFile() {
    GltfWriter w;
    std::vector<int> nodes;
    int layer = 0;
    for (const int rings : {24, 32}) {
        const TriangleMesh sphere = test::makeUvSphere(glm::dvec3(0.0), 1.0, rings, 2 * rings);
        std::vector<float> xyz;
        for (const glm::vec3 &p : sphere.positions) xyz.insert(xyz.end(), {p.x, p.y, p.z});
        std::vector<std::uint32_t> idx;
        for (const glm::uvec3 &t : sphere.indices) idx.insert(idx.end(), {t.x, t.y, t.z});
        const int m = w.mesh({{"attributes", {{"POSITION", w.positions(xyz)}}}, {"indices", w.indices32(idx)}});
        nodes.push_back(w.node({{"mesh", m},
                                {"name", layer == 0 ? "housing" : "part"},
                                {"translation", {1e7, 0.0, 0.0}},
                                {"extras", {{"layer", layer}}}}));
        ++layer;
    }
    w.scene(nodes);
    const fs::path path =
        outDir() / ("touching-spheres-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".gltf");
    std::ofstream(path) << w.text();
    return path.string();
}

TEST(RenderLayerContactCli, InfoSuggestsAToleranceForTouchingLayersTriangulatedDifferently) {
    const std::string file = quoted(touchingSpheresFile());
    const CommandResult r = runRender(file + " --info");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("contact    off"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("layers 0 and 1 nearly touch"), std::string::npos) << r.output;
    const std::size_t at = r.output.find("suggested: --layer-contact ");
    ASSERT_NE(at, std::string::npos) << r.output;
    const std::string value = r.output.substr(at + 27, r.output.find(' ', at + 27) - (at + 27));
    // The outer facets' sagitta (their quads' diagonal), 1 − cos(√2·π/48) of the radius, over
    // the diagonal 2√3: 1.23e-3. The suggestion is 1.5 × the largest separation sampled.
    const double suggested = std::stod(value);
    EXPECT_GT(suggested, 0.5 * 1.23e-3) << r.output;
    EXPECT_LT(suggested, 2.0 * 1.23e-3) << r.output;

    const CommandResult set = runRender(file + " --info --layer-contact " + value);
    ASSERT_EQ(set.exitCode, 0) << set.output;
    EXPECT_NE(set.output.find("contact    --layer-contact " + value), std::string::npos) << set.output;
}

TEST(RenderLayerContactCli, SessionFilesCarryTheToleranceAndTheCommandLineWins) {
    const std::string file = touchingSpheresFile();
    const fs::path session = outDir() / "touching-session.json";
    std::ofstream(session) << R"({"version": 1, "scene": ")" << file
                           << R"(", "layerContact": {"sceneUnits": 0.002}, "lenses": []})";
    const CommandResult r = runRender("--lenses " + quoted(session.string()) + " --info");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("contact    --layer-contact 0.002 units"), std::string::npos) << r.output;
    const CommandResult wins = runRender("--lenses " + quoted(session.string()) + " --info --layer-contact 1e-4");
    EXPECT_NE(wins.output.find("contact    --layer-contact 0.0001\n"), std::string::npos) << wins.output;

    // --save-lenses writes it back.
    const fs::path saved = outDir() / "touching-saved.json";
    const CommandResult save = runRender("--lenses " + quoted(session.string()) + " --size 8x8 --spp 1 -o " +
                                         quoted((outDir() / "touching.png").string()) + " --save-lenses " +
                                         quoted(saved.string()));
    ASSERT_EQ(save.exitCode, 0) << save.output;
    std::ifstream in(saved);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"layerContact\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"sceneUnits\": 0.002"), std::string::npos) << text;

    std::ofstream(session) << R"({"version": 1, "scene": ")" << file << R"(", "layerContact": {"relative": -1}})";
    const CommandResult bad = runRender("--lenses " + quoted(session.string()) + " --info");
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("touching-session.json: layerContact.relative: "), std::string::npos) << bad.output;
}

TEST(RenderLayerContactCli, BadValuesAreUsageErrors) {
    for (const char *value : {"-1", "x", "1e-3mm", "inf"}) {
        const CommandResult r = runRender(std::string("builtin:onion --info --layer-contact ") + value);
        EXPECT_EQ(r.exitCode, 2) << value << "\n" << r.output;
        EXPECT_NE(r.output.find("mvcl-render: command line: --layer-contact: "), std::string::npos) << r.output;
    }
}

} // namespace
} // namespace mvcl
