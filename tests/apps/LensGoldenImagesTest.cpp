// Every demo lens stack in assets/lenses is also a regression test: rendered through mvcl-render
// (plugins loaded at run time, the file read, the stack composed, outlines drawn) and compared
// with tests/golden/lenses-<name>.png. Regenerate with MVCL_UPDATE_GOLDEN=1 after an intended
// change, and look at the images before committing them.

#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace mvcl;
using namespace mvcl::test;

namespace {

fs::path assetsDir() { return fs::path(MVCL_TEST_DATA_DIR) / ".." / ".." / "assets" / "lenses"; }

std::vector<std::string> demoStacks() {
    std::vector<std::string> names;
    for (const fs::directory_entry &e : fs::directory_iterator(assetsDir()))
        if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

class LensGoldenImages : public testing::TestWithParam<std::string> {};

} // namespace

TEST(LensGoldenImages, TheDemoStacksOfThePaperScenesExist) {
    const std::vector<std::string> names = demoStacks();
    for (const char *needed : {"cube-in-cube", "HRA_Female_Body", "2CylinderEngine"})
        EXPECT_NE(std::find(names.begin(), names.end(), needed), names.end()) << needed;
}

TEST_P(LensGoldenImages, RendersAsTheGoldenImage) {
    const std::string name = GetParam();
    const fs::path stack = assetsDir() / (name + ".json");
    const fs::path out = outDir() / ("lenses-" + name + ".png");
    const fs::path golden = fs::path(MVCL_GOLDEN_DIR) / ("lenses-" + name + ".png");
    fs::remove(out);
    const CommandResult r = runRender("--lenses " + quoted(stack.string()) + " --size 200x150 --spp 2 -o " +
                                      quoted(out.string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fs::exists(out)) << r.output;
    // Each lens of the stack must have pixels under it: a lens that misses the view tests nothing.
    EXPECT_EQ(r.output.find(": 0 px"), std::string::npos) << r.output;
    MVCL_EXPECT_MATCHES_GOLDEN(out, golden);
}

INSTANTIATE_TEST_SUITE_P(Demos, LensGoldenImages, testing::ValuesIn(demoStacks()),
                         [](const testing::TestParamInfo<std::string> &info) {
                             std::string id = info.param;
                             std::replace_if(id.begin(), id.end(), [](char c) { return !std::isalnum(c); }, '_');
                             return id;
                         });
