// mvcl-render as a user runs it: exit codes, messages, and every shared model rendered.

#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

/// Mean luminance spread of an image: a blank (single-colour) image has zero.
double imageVariance(const mvcl::Framebuffer &f) {
    double sum = 0, sum2 = 0;
    for (const glm::vec3 &p : f.pixels()) {
        const double y = 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
        sum += y;
        sum2 += y * y;
    }
    const double n = double(f.pixels().size());
    return sum2 / n - (sum / n) * (sum / n);
}

} // namespace

TEST(RenderCli, HelpAndVersionExitZero) {
    const CommandResult help = runRender("--help");
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.output.find("Exit codes"), std::string::npos);
    EXPECT_EQ(runRender("--version").exitCode, 0);
}

TEST(RenderCli, BadArgumentsExitTwoWithOneLineError) {
    for (const char *args : {"", "--bogus builtin:onion", "builtin:onion --spp 0", "builtin:onion --size 10",
                             "builtin:onion --eye 1,2", "builtin:onion --fov 200", "a.glb b.glb",
                             "builtin:onion --threads", "builtin:onion --adaptive --target-error -1",
                             "builtin:onion --target-error x", "builtin:onion --time-limit 0",
                             "builtin:onion --max-spp 0", "builtin:onion --spp 8 --max-spp 4",
                             "builtin:onion --time-limit inf"}) {
        const CommandResult r = runRender(args);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("mvcl-render: command line:"), std::string::npos) << args << "\n" << r.output;
    }
}

TEST(RenderCli, MissingOrUnknownSceneExitsOneNamingIt) {
    for (const std::string &src : {std::string("/nonexistent/model.glb"), std::string("builtin:teapot"),
                                   std::string("notes.txt")}) {
        const CommandResult r = runRender(src + " --info");
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find(src.substr(src.find_last_of("/:") + 1)), std::string::npos) << r.output;
    }
}

TEST(RenderCli, InfoPrintsLayersWithoutRendering) {
    const CommandResult r = runRender("builtin:cube-in-cube --info");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("triangles  24"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("inner cube"), std::string::npos);
    EXPECT_EQ(r.output.find("wrote"), std::string::npos);
}

TEST(RenderCli, EmptySceneLoadsAndRendersBackground) {
    const std::string empty = quoted(dataPath("models/EdgeCases/assimp/TestNoRootNode/SceneWithoutNodes.gltf"));
    const CommandResult info = runRender(empty + " --info");
    EXPECT_EQ(info.exitCode, 0) << info.output;
    EXPECT_NE(info.output.find("triangles  0"), std::string::npos) << info.output;
    const fs::path out = outDir() / "empty.png";
    const CommandResult render = runRender(empty + " --size 16x16 -o " + out.string());
    EXPECT_EQ(render.exitCode, 0) << render.output;
    EXPECT_TRUE(fs::exists(out));
}

TEST(RenderCli, DefaultSceneRendersAndReportsThroughput) {
    const fs::path out = outDir() / "default.png";
    fs::remove(out);
    const CommandResult r = runRender("builtin:cube-in-cube --size 160x120 --spp 1 -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char *key : {"bvh", "render", "Mrays/s", "wrote"})
        EXPECT_NE(r.output.find(key), std::string::npos) << key << "\n" << r.output;
    ASSERT_TRUE(fs::exists(out));
    EXPECT_GT(imageVariance(mvcl::readImage(out)), 1e-4);
}

TEST(RenderCli, AdaptiveRenderReportsSamplesReachedAndEstimatedError) {
    const fs::path out = outDir() / "adaptive.png";
    const CommandResult r =
        runRender("builtin:cube-in-cube --size 80x60 --spp 2 --adaptive --max-spp 32 --target-error 0.02 -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("adaptive 2..32 spp, target error 0.02"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("samples    2 min,"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("32 max per pixel; estimated error"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(out));
}

TEST(RenderCli, TimeLimitStopsAProgressiveRender) {
    const CommandResult r = runRender("builtin:cube-in-cube --size 64x48 --time-limit 0.2 --max-spp 100000 -o " +
                                      (outDir() / "time-limit.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("progressive 1..100000 spp"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("100000 max per pixel"), std::string::npos) << "the time limit did not stop it\n" << r.output;
}

TEST(RenderCli, FileCamerasAreSelectableByIndex) {
    const std::string duck = quoted(dataPath("models/Duck/Duck.glb"));
    const fs::path out = outDir() / "duck-camera.png";
    const CommandResult ok = runRender(duck + " --camera 0 --size 64x48 --spp 1 -o " + out.string());
    EXPECT_EQ(ok.exitCode, 0) << ok.output;
    const CommandResult bad = runRender(duck + " --camera 3 --size 64x48 -o " + out.string());
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("1 cameras"), std::string::npos) << bad.output;
}

TEST(RenderCli, LayerRulesOverrideInference) {
    const std::string kidney = quoted(dataPath("models/HRA_Kidney_Female_Left/VH_F_Kidney_L.glb"));
    const CommandResult r = runRender(kidney + " --info --layer-rule '*pyramid*=5;*capsule*=0'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("VH_F_renal_pyramid_L_a"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("layer 5 (rule)"), std::string::npos) << r.output;
    const CommandResult bad = runRender(kidney + " --info --layer-rule '*pyramid*'");
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    const fs::path rules = outDir() / "bad-rules.json";
    std::ofstream(rules) << "{\"rules\": [{\"match\": \"*\", \"layer\": 99}]}";
    const CommandResult badFile = runRender(kidney + " --info --layer-rules " + rules.string());
    EXPECT_EQ(badFile.exitCode, 1) << badFile.output;
    EXPECT_NE(badFile.output.find("bad-rules.json"), std::string::npos) << badFile.output;
}

TEST(RenderCli, ForcingEveryStageGivesTheSameImageAndReportsNothingSkipped) {
    // A shadow lens whose casters exist nowhere: skipping leaves its shadow rays out.
    const std::string args = "builtin:cube-in-cube --size 96x72 --spp 1 --lens "
                             "'shadow:shape=rectangle,center=[0.5,0.5],size=[0.6,0.6],casters=none'";
    const fs::path skipped = outDir() / "stages-skipped.exr";
    const fs::path forced = outDir() / "stages-forced.exr";
    const CommandResult skipping = runRender(args + " -o " + skipped.string());
    ASSERT_EQ(skipping.exitCode, 0) << skipping.output;
    const CommandResult forcing = runRender(args + " --force-all-stages -o " + forced.string());
    ASSERT_EQ(forcing.exitCode, 0) << forcing.output;
    EXPECT_NE(skipping.output.find("skipped    "), std::string::npos) << skipping.output;
    EXPECT_NE(skipping.output.find("M rays saved"), std::string::npos) << skipping.output;
    EXPECT_EQ(skipping.output.find("skipped    0.000 M shadow rays"), std::string::npos) << skipping.output;
    EXPECT_NE(forcing.output.find("skipped    nothing: every stage forced"), std::string::npos) << forcing.output;
    const mvcl::Framebuffer a = mvcl::readImage(skipped), b = mvcl::readImage(forced);
    EXPECT_EQ(a.pixels(), b.pixels());
}

TEST(RenderCli, NoDefaultLightsLeavesAFileWithoutLightsUnlit) {
    const std::string box = quoted(dataPath("models/Box/Box.glb"));
    const CommandResult lit = runRender(box + " --info");
    ASSERT_EQ(lit.exitCode, 0) << lit.output;
    EXPECT_NE(lit.output.find("2 lights"), std::string::npos) << lit.output;
    const CommandResult unlit = runRender(box + " --no-default-lights --info");
    ASSERT_EQ(unlit.exitCode, 0) << unlit.output;
    EXPECT_NE(unlit.output.find("0 lights"), std::string::npos) << unlit.output;
    const CommandResult render = runRender(box + " --no-default-lights --size 32x24 --spp 1 -o " +
                                           (outDir() / "box-unlit.png").string());
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_NE(render.output.find("shadow 0.000 M"), std::string::npos) << render.output;
}

TEST(RenderCli, UnwritableOutputExitsThree) {
    const CommandResult r = runRender("builtin:onion --size 8x8 -o /proc/forbidden/x.png");
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("/proc/forbidden/x.png"), std::string::npos) << r.output;
}

// Every real model of the shared corpus renders to an image that is not blank.
class RenderCliModel : public ::testing::TestWithParam<const char *> {};

TEST_P(RenderCliModel, RendersToANonBlankImage) {
    const std::string model = dataPath(GetParam());
    const fs::path out = outDir() / (fs::path(model).stem().string() + ".png");
    fs::remove(out);
    const CommandResult r = runRender(quoted(model) + " --size 96x72 --spp 1 -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fs::exists(out));
    EXPECT_GT(imageVariance(mvcl::readImage(out)), 1e-4) << "blank image for " << model;
}

INSTANTIATE_TEST_SUITE_P(SharedModels, RenderCliModel,
                         ::testing::Values("models/Box/Box.glb", "models/Duck/Duck.glb",
                                           "models/Avocado/Avocado.glb",
                                           "models/2CylinderEngine/2CylinderEngine.glb",
                                           "models/MosquitoInAmber/MosquitoInAmber.glb",
                                           "models/HRA_Kidney_Female_Left/VH_F_Kidney_L.glb",
                                           "models/HRA_Female_Body/HRA_Female_Body.glb"),
                         [](const auto &info) {
                             std::string n = fs::path(info.param).stem().string();
                             for (char &c : n)
                                 if (!std::isalnum((unsigned char)c)) c = '_';
                             return n;
                         });

// Each invalid file of the EdgeCases corpus marked REJECT fails with exit 1 and names the file.
TEST(RenderCli, RejectedEdgeCasesExitOneNamingTheFile) {
    std::ifstream index(dataPath("models/EdgeCases/INDEX.tsv"));
    ASSERT_TRUE(index) << "INDEX.tsv missing";
    std::string line;
    std::getline(index, line); // header
    int rejected = 0;
    while (std::getline(index, line)) {
        std::stringstream ss(line);
        std::string file, errors, warnings, expectation;
        std::getline(ss, file, '\t');
        std::getline(ss, errors, '\t');
        std::getline(ss, warnings, '\t');
        std::getline(ss, expectation, '\t');
        if (expectation != "REJECT") continue;
        const CommandResult r = runRender(quoted(dataPath("models/EdgeCases/" + file)) + " --info");
        EXPECT_EQ(r.exitCode, 1) << file << "\n" << r.output;
        EXPECT_NE(r.output.find(fs::path(file).filename().string()), std::string::npos) << r.output;
        ++rejected;
    }
    EXPECT_GE(rejected, 10);
}
