// Renaming a layer in mvcl-viewer (Xvfb) by script: the name is saved in the session, an undo
// (Ctrl+Z) brings the old one back, a second viewer opening the session shows the new name, and a
// layer the scene does not have fails the script naming the line.

#include "apps/RenderCliRunner.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

CommandResult runViewer(const std::string &args) {
    return runCommand("xvfb-run -a -s '-screen 0 1400x900x24' " + std::string(MVCL_VIEWER_EXE) +
                      " --size 1280x720 --sampling fixed --spp 1 " + args);
}

nlohmann::json readJson(const fs::path &file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return nlohmann::json::parse(text.str());
}

} // namespace

TEST(ViewerEndToEnd, ALayerRenamedByScriptIsUndoableAndSavedInTheSession) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = outDir() / "viewer" / "layer-names";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path undone = dir / "undone.json", renamed = dir / "renamed.json", again = dir / "again.json";

    std::ofstream(dir / "rename.txt") << "set-layer-name 1 kidney\nsave-session " << renamed.string()
                                      << "\nkey Z ctrl\nsave-session " << undone.string() << "\nquit\n";
    const CommandResult run = runViewer("builtin:cube-in-cube --script " + quoted((dir / "rename.txt").string()));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(readJson(renamed).at("layerNames"), (nlohmann::json{{"1", "kidney"}}));
    EXPECT_FALSE(readJson(undone).contains("layerNames")) << "undone: the scene's own name again";

    // A second viewer shows the saved name and saves it back.
    std::ofstream(dir / "reopen.txt") << "save-session " << again.string() << "\nquit\n";
    const CommandResult reopen = runViewer("--session " + quoted(renamed.string()) + " --script " +
                                           quoted((dir / "reopen.txt").string()));
    ASSERT_EQ(reopen.exitCode, 0) << reopen.output;
    EXPECT_EQ(readJson(again).at("layerNames"), (nlohmann::json{{"1", "kidney"}}));

    std::ofstream(dir / "bad.txt") << "set-layer-name 9 bone\nquit\n";
    const CommandResult bad = runViewer("builtin:cube-in-cube --script " + quoted((dir / "bad.txt").string()));
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("layer 9: the scene has no such layer"), std::string::npos) << bad.output;
}
