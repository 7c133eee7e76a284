// mvcl-viewer opening a model while it runs (Xvfb + Mesa llvmpipe): the load runs beside the
// live window, the scene as read shows first, its inferred layers follow, the lenses stay; a
// broken file is reported and the scene on screen stays.

#include "apps/RenderCliRunner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

CommandResult runViewerScript(const fs::path &script, const std::string &text) {
    std::ofstream(script) << text;
    return runCommand("xvfb-run -a -s '-screen 0 1400x900x24' " + std::string(MVCL_VIEWER_EXE) +
                      " builtin:cube-in-cube --size 1280x720 --sampling fixed --spp 2 --script " + script.string());
}

} // namespace

TEST(OpenViewerEndToEnd, AModelOpensBesideTheLiveWindowAndKeepsTheLenses) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = outDir() / "viewer-open";
    fs::create_directories(dir);
    const fs::path shot = dir / "engine.png";
    fs::remove(shot);
    const std::string engine = dataPath("models/2CylinderEngine/2CylinderEngine.glb");
    const CommandResult r = runViewerScript(dir / "open.txt", "wait-converged\nadd-lens layer 0.5 0.5\nopen " + engine +
                                                                  "\nexpect-lenses 1\nwait-converged\nscreenshot " +
                                                                  shot.string() + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("showing " + engine + " after "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("; inferring its layers"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("layers of " + engine + " inferred after "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("first image after "), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(shot)) << r.output;
}

TEST(OpenViewerEndToEnd, ABrokenFileIsReportedAndTheSceneStays) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = outDir() / "viewer-open";
    fs::create_directories(dir);
    const fs::path broken = dir / "broken.glb";
    std::ofstream(broken, std::ios::binary) << "glTF? no";
    const CommandResult r = runViewerScript(dir / "broken.txt", "wait-converged\nadd-lens layer 0.5 0.5\nopen " +
                                                                    broken.string() +
                                                                    "\nexpect-lenses 1\nwait-converged\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(broken.string()), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("showing "), std::string::npos) << r.output;
}
