// mvcl-render and sessions of several views: --view N renders one view, --view all every view
// side by side (the same pixels as each alone), a view in compare mode splits its stacks, and
// bad --view values are usage errors.

#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <mvcl/view/ImageIO.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

/// Two views of the cube in a cube: the first with the outer cube hidden, the second from
/// another side with a compare split (no lens left, a reveal lens right).
fs::path twoViewSession() {
    const fs::path file = outDir() / "two-views.json";
    std::ofstream(file) << R"({"version": 2, "scene": "builtin:cube-in-cube",
        "views": [{"camera": {"eye": [0.5, 3.6, 7.5], "target": [0, 0.9, 0]}, "visibleLayers": "1-"},
                  {"camera": {"eye": [6, 2, 3], "target": [0, 0.9, 0]},
                   "compare": {"divider": 0.5, "lenses": [{"type": "layer",
                       "region": {"shape": "rectangle", "center": [0.5, 0.5], "size": [1, 1]},
                       "properties": {"layers": "1-"}}]}}],
        "links": [{"views": [0, 1], "layers": false, "camera": false, "lenses": false}],
        "layout": "1x2"})";
    return file;
}

} // namespace

TEST(RenderViewsCli, ViewAllIsEveryViewSideBySide) {
    const fs::path session = twoViewSession(), dir = outDir();
    const std::string common = "--lenses " + quoted(session.string()) + " --size 64x48 --spp 1 ";
    for (const char *view : {"0", "1"}) {
        const CommandResult one = runRender(common + "--view " + view + " -o " + quoted((dir / (std::string("view") + view + ".png")).string()));
        ASSERT_EQ(one.exitCode, 0) << one.output;
    }
    const CommandResult all = runRender(common + "--view all -o " + quoted((dir / "all.png").string()));
    ASSERT_EQ(all.exitCode, 0) << all.output;
    EXPECT_NE(all.output.find("views      2 of"), std::string::npos) << all.output;
    const mvcl::Framebuffer side = mvcl::readImage(dir / "all.png");
    ASSERT_EQ(side.width(), 128);
    ASSERT_EQ(side.height(), 48);
    const mvcl::Framebuffer view0 = mvcl::readImage(dir / "view0.png"), view1 = mvcl::readImage(dir / "view1.png");
    int differing = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            EXPECT_EQ(side.at(x, y), view0.at(x, y));
            EXPECT_EQ(side.at(64 + x, y), view1.at(x, y));
            differing += !(view0.at(x, y) == view1.at(x, y));
        }
    EXPECT_GT(differing, 100);

    // View 1 compares two stacks: its left half is the plain view, its right half the lens's.
    const CommandResult plain = runRender("builtin:cube-in-cube --eye 6,2,3 --target 0,0.9,0 --size 64x48 --spp 1 -o " +
                                          quoted((dir / "plain.png").string()));
    ASSERT_EQ(plain.exitCode, 0) << plain.output;
    const mvcl::Framebuffer reference = mvcl::readImage(dir / "plain.png");
    int rightDiffers = 0;
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 31; ++x) EXPECT_EQ(view1.at(x, y), reference.at(x, y)) << x << "," << y;
        for (int x = 33; x < 64; ++x) rightDiffers += !(view1.at(x, y) == reference.at(x, y));
    }
    EXPECT_GT(rightDiffers, 50);
}

TEST(RenderViewsCli, BadViewValuesAreUsageErrors) {
    const fs::path session = twoViewSession();
    const CommandResult missing = runRender("--lenses " + quoted(session.string()) + " --view 2 -o /dev/null");
    EXPECT_EQ(missing.exitCode, 2) << missing.output;
    EXPECT_NE(missing.output.find("view 2 of " + session.string() + ": the file has 2 views (0..1)"), std::string::npos)
        << missing.output;
    const CommandResult word = runRender("--lenses " + quoted(session.string()) + " --view left");
    EXPECT_EQ(word.exitCode, 2) << word.output;
    EXPECT_NE(word.output.find("--view: expected a view number (0, 1, ...) or 'all', got 'left'"), std::string::npos)
        << word.output;
    const CommandResult noFile = runRender("builtin:cube-in-cube --view 0");
    EXPECT_EQ(noFile.exitCode, 2) << noFile.output;
    EXPECT_NE(noFile.output.find("--view picks a view of the --lenses session"), std::string::npos) << noFile.output;
}
