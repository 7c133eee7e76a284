// mvcl-viewer with two views in a real window (Xvfb + Mesa llvmpipe): linked cameras, a lens in
// each view, an orbit in one; the screenshot (every view as laid out) must match the committed
// baseline and a reopened session must show the same. Regenerate the baseline with
// MVCL_UPDATE_GOLDEN=1. The new script commands are checked before any window opens.

#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <mvcl/io/SessionFile.h>
#include <mvcl/lens/LensRegistry.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

fs::path viewsDir() {
    const fs::path dir = outDir() / "viewer-views";
    fs::create_directories(dir);
    return dir;
}

/// As the other viewer tests: a 1280×720 window, a 900×720 image area (two 450×720 views).
CommandResult runViewer(const std::string &args) {
    return runCommand("xvfb-run -a -s '-screen 0 1400x900x24' " + std::string(MVCL_VIEWER_EXE) +
                      " --size 1280x720 --sampling fixed --spp 4 " + args);
}

mvcl::SessionDescription readSession(const fs::path &file) {
    static mvcl::LensRegistry registry;
    if (registry.lensTypes().empty())
        for (const char *type : {"layer", "achromatic"})
            registry.loadModule(fs::path(MVCL_PLUGIN_BUILD_DIR) / ("mvcl-lens-" + std::string(type) + ".so"));
    return mvcl::readSessionFile(file, registry);
}

} // namespace

TEST(ViewerEndToEnd, TwoViewsWithLinkedCamerasFollowAnOrbitAndReopenTheSame) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewsDir();
    const fs::path before = dir / "before.json", session = dir / "two.json", first = dir / "first.png",
                   second = dir / "second.png";
    for (const fs::path &f : {before, session, first, second}) fs::remove(f);
    const std::string kidney = dataPath("models/HRA_Kidney_Female_Left/VH_F_Kidney_L.glb");
    std::ofstream(dir / "build.txt") << R"(# two views side by side, cameras linked, a lens in each, an orbit in view 1
layout 1x2
link camera 0 1
focus-view 0
add-lens layer 0.5 0.45
set-property 0 layers 1-
focus-view 1
add-lens achromatic 0.5 0.6
expect-lenses 1
save-session )" << before.string() << R"(
drag left 40 60 160 110 6
wait-converged
screenshot )" << first.string() << R"(
save-session )" << session.string() << R"(
quit
)";
    const CommandResult build = runViewer(quoted(kidney) + " --script " + quoted((dir / "build.txt").string()));
    ASSERT_EQ(build.exitCode, 0) << build.output;
    ASSERT_TRUE(fs::exists(first)) << build.output;

    // The orbit was in view 1; view 0 followed it through the link.
    const mvcl::SessionDescription start = readSession(before), end = readSession(session);
    ASSERT_EQ(end.views.size(), 2u);
    EXPECT_EQ(end.layout, mvcl::ViewLayout::Columns);
    ASSERT_EQ(end.links.size(), 1u);
    EXPECT_TRUE(end.links[0].camera);
    EXPECT_EQ(end.views[0].camera, end.views[1].camera);
    EXPECT_NE(end.views[0].camera, start.views[0].camera);
    EXPECT_EQ(end.views[0].lenses.size(), 1);
    EXPECT_EQ(end.views[1].lenses.size(), 1);
    EXPECT_EQ(end.views[0].lenses.lens(0)->typeName(), "layer");
    EXPECT_EQ(end.views[1].lenses.lens(0)->typeName(), "achromatic");

    const mvcl::Framebuffer a = mvcl::readImage(first);
    EXPECT_EQ(a.width(), 900);
    EXPECT_EQ(a.height(), 720);

    std::ofstream(dir / "reopen.txt") << "wait-converged\nexpect-lenses 1\nscreenshot " << second.string() << "\nquit\n";
    const CommandResult reopen =
        runViewer("--session " + quoted(session.string()) + " --script " + quoted((dir / "reopen.txt").string()));
    ASSERT_EQ(reopen.exitCode, 0) << reopen.output;
    const ImageDifference same = compareImages(a, mvcl::readImage(second), 2);
    EXPECT_LT(same.differingFraction, 0.001) << "max channel delta " << same.maxChannelDelta;

    MVCL_EXPECT_MATCHES_GOLDEN(first, fs::path(MVCL_GOLDEN_DIR) / "viewer-two-linked-views.png");
}

TEST(ViewerEndToEnd, BadViewCommandsFailBeforeTheWindowOpens) {
    const fs::path dir = viewsDir();
    const std::pair<const char *, const char *> cases[] = {
        {"layout 3x3\n", "layout: unknown layout '3x3' (known: 1, 1x2, 2x1, 2x2)"},
        {"focus-view 7\n", "focus-view: view 7 does not exist (views 0..3)"},
        {"link camera 1 1\n", "link: a view cannot be linked to itself"},
        {"unlink colour 0 1\n", "unlink: unknown link 'colour' (known: camera, lenses, layers)"},
        {"compare maybe\n", "compare: expects on or off, got 'maybe'"},
        {"compare-divider 1.5\n", "compare-divider: the divider is a fraction of the view's width, 0..1, got 1.5"},
    };
    for (const auto &[script, message] : cases) {
        std::ofstream(dir / "bad.txt") << "wait-converged\n" << script;
        const CommandResult bad = runCommand("env -u DISPLAY " + std::string(MVCL_VIEWER_EXE) + " builtin:onion --script " +
                                             quoted((dir / "bad.txt").string()));
        EXPECT_EQ(bad.exitCode, 2) << bad.output;
        EXPECT_NE(bad.output.find(std::string("bad.txt:2: ") + message), std::string::npos) << bad.output;
    }
}
