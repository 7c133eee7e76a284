// mvcl-render with lenses: --lens, --lenses, --save-lenses, --list-lenses, and their errors.

#include "apps/RenderCliRunner.h"

#include <mvcl/view/ImageIO.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

const char *const kSmall = " --size 96x72 --spp 1";

fs::path assetPath(const std::string &name) { return fs::path(MVCL_TEST_DATA_DIR) / ".." / ".." / "assets" / "lenses" / name; }

std::string readText(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

long lineCount(const std::string &text) { return long(std::count(text.begin(), text.end(), '\n')); }

} // namespace

TEST(RenderLensCli, DocsHoldTheGeneratedPropertyTablesOfEveryLens) {
    // docs/lenses.md carries the output of --list-lenses --format markdown between two markers;
    // a lens whose declarations change without the docs fails here. Regenerate the block with
    //   build/bin/mvcl-render --list-lenses --format markdown
    const CommandResult r = runRender("--list-lenses --format markdown");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char *type : {"clip", "layer", "peel", "xray"})
        EXPECT_NE(r.output.find(std::string("#### ") + type + "\n"), std::string::npos) << type;
    EXPECT_NE(r.output.find("| `rays` | ray-type set | `primary` | all\\|none\\|"), std::string::npos)
        << "'|' inside a cell is escaped\n" << r.output;
    const std::string docs = readText(fs::path(MVCL_TEST_DATA_DIR) / ".." / ".." / "docs" / "lenses.md");
    const std::string begin = "<!-- generated: mvcl-render --list-lenses --format markdown -->\n";
    const std::string end = "<!-- end of generated tables -->";
    const std::size_t from = docs.find(begin), to = docs.find(end);
    ASSERT_NE(from, std::string::npos) << "docs/lenses.md has no generated block";
    ASSERT_NE(to, std::string::npos);
    EXPECT_EQ(docs.substr(from + begin.size(), to - from - begin.size()), r.output)
        << "docs/lenses.md's property tables differ from the lenses' declarations: regenerate them";
}

TEST(RenderLensCli, ListFormatMustBeTextOrMarkdown) {
    const CommandResult r = runRender("--list-lenses --format html");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--format"), std::string::npos) << r.output;
}

TEST(RenderLensCli, ListLensesShowsEveryLensWithItsPropertyTable) {
    const CommandResult r = runRender("--list-lenses");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char *expected : {"layer:", "achromatic:", "shadow:", "property", "default", "range", "layers",
                                 "distance", "amount", "casters", "strength", "tint", "rays", "scene units"})
        EXPECT_NE(r.output.find(expected), std::string::npos) << expected << "\n" << r.output;
}

// A lens changes the pixels under it and nothing else.
TEST(RenderLensCli, LensOnTheCommandLineChangesOnlyItsRegion) {
    const fs::path plain = outDir() / "lens-plain.png";
    const fs::path lensed = outDir() / "lens-cli.png";
    fs::remove(lensed);
    const CommandResult base = runRender(std::string("builtin:cube-in-cube") + kSmall + " -o " + plain.string());
    ASSERT_EQ(base.exitCode, 0) << base.output;
    const CommandResult r = runRender(std::string("builtin:cube-in-cube") + kSmall + " -o " + lensed.string() +
                                      " --lens 'layer:shape=rectangle,center=[0.5,0.5],size=[0.5,0.5],layers=1-,label=core'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("lens 0 layer 'core': 1,728 px"), std::string::npos) << r.output; // 48 × 36
    EXPECT_NE(r.output.find("policies"), std::string::npos) << r.output;
    ASSERT_TRUE(fs::exists(lensed));

    const mvcl::Framebuffer a = mvcl::readImage(plain), b = mvcl::readImage(lensed);
    ASSERT_EQ(a.width(), b.width());
    int changedInside = 0, changedOutside = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const bool inside = x >= 24 && x < 72 && y >= 18 && y < 54;
            if (a.at(x, y) != b.at(x, y)) ++(inside ? changedInside : changedOutside);
        }
    EXPECT_GT(changedInside, 200); // the outer cube is gone under the lens
    EXPECT_EQ(changedOutside, 0);
}

TEST(RenderLensCli, ShippedLensFilesRender) {
    for (const char *name : {"cube-in-cube.json", "2CylinderEngine.json", "HRA_Female_Body.json"}) {
        const fs::path out = outDir() / (fs::path(name).stem().string() + "-lenses.png");
        fs::remove(out);
        // No scene on the command line: the file names it (relative to the file).
        const CommandResult r = runRender("--lenses " + quoted(assetPath(name).string()) + kSmall + " -o " + out.string());
        EXPECT_EQ(r.exitCode, 0) << name << "\n" << r.output;
        EXPECT_NE(r.output.find("lens 0 layer"), std::string::npos) << r.output;
        EXPECT_TRUE(fs::exists(out)) << name;
    }
}

// --lens adds on top of --lenses; --save-lenses writes the effective stack, which loads back to
// the same stack (saving it again gives the same file).
TEST(RenderLensCli, SavedStackReloadsToTheSameStack) {
    const fs::path first = outDir() / "saved-1.json";
    const fs::path second = outDir() / "saved-2.json";
    const fs::path image = outDir() / "saved.png";
    fs::remove(first);
    fs::remove(second);
    const CommandResult save = runRender("--lenses " + quoted(assetPath("cube-in-cube.json").string()) +
                                         " --lens 'achromatic:amount=0.5,shape=polygon,points=[[0,0],[0.3,0],[0,0.3]]'" +
                                         " --layer-rule '*inner*=1'" + kSmall + " -o " + image.string() +
                                         " --save-lenses " + first.string());
    ASSERT_EQ(save.exitCode, 0) << save.output;
    EXPECT_NE(save.output.find("lens 3 achromatic"), std::string::npos) << save.output;
    const std::string saved = readText(first);
    for (const char *expected : {"\"scene\": \"builtin:cube-in-cube\"", "\"eye\"", "\"*inner*\"", "\"amount\": \"0.5\"",
                                 "\"tinted shadows\"", "\"polygon\""})
        EXPECT_NE(saved.find(expected), std::string::npos) << expected << "\n" << saved;

    const CommandResult reload = runRender("--lenses " + first.string() + kSmall + " -o " + image.string() +
                                           " --save-lenses " + second.string());
    ASSERT_EQ(reload.exitCode, 0) << reload.output;
    EXPECT_EQ(readText(second), saved);
}

TEST(RenderLensCli, BadLensSpecsExitTwoWithOneLineNamingTheProblem) {
    const struct {
        const char *spec;
        const char *named;
    } cases[] = {
        {"layer:strenght=1", "strenght"},
        {"nosuchlens:amount=1", "nosuchlens"},
        {"layer:center=[0.5,0.5", "'[' without ']'"},
        {"layer:size=[-0.1,0.3]", "size"},
        {"achromatic:amount=2", "amount"},
    };
    for (const auto &c : cases) {
        const CommandResult r = runRender(std::string("builtin:onion --size 8x8 --lens '") + c.spec + "'");
        EXPECT_EQ(r.exitCode, 2) << c.spec << "\n" << r.output;
        EXPECT_EQ(lineCount(r.output), 1) << r.output;
        EXPECT_EQ(r.output.rfind("mvcl-render: command line: --lens: ", 0), 0u) << r.output;
        EXPECT_NE(r.output.find(c.named), std::string::npos) << r.output;
    }
    EXPECT_EQ(runRender("builtin:onion --lens").exitCode, 2);
}

TEST(RenderLensCli, BadLensFilesExitOneWithOneLineNamingTheFile) {
    const fs::path file = outDir() / "bad-stack.json";
    for (const std::string &json : {std::string(R"({"lenses": [{"type": "shadow", "properties": {"strenght": 1}}]})"),
                                    std::string(R"({"lenses": [{"type": "nosuchlens"}]})"),
                                    std::string(R"({"lenses": [)"), std::string(R"({"scene": "builtin:onion", "zoom": 2})")}) {
        std::ofstream(file) << json;
        const CommandResult r = runRender("builtin:onion --size 8x8 --lenses " + file.string());
        EXPECT_EQ(r.exitCode, 1) << json << "\n" << r.output;
        EXPECT_EQ(lineCount(r.output), 1) << r.output;
        EXPECT_NE(r.output.find("bad-stack.json: "), std::string::npos) << r.output;
    }
    const CommandResult missing = runRender("--lenses /nonexistent/stack.json");
    EXPECT_EQ(missing.exitCode, 1) << missing.output;
    EXPECT_NE(missing.output.find("/nonexistent/stack.json"), std::string::npos) << missing.output;

    std::ofstream(file) << R"({"lenses": []})";
    const CommandResult noScene = runRender("--lenses " + file.string());
    EXPECT_EQ(noScene.exitCode, 2) << noScene.output;
    EXPECT_NE(noScene.output.find("no scene"), std::string::npos) << noScene.output;
}

TEST(RenderLensCli, UnwritableSaveLensesExitsThree) {
    const CommandResult r = runRender("builtin:onion --size 8x8 --save-lenses /proc/forbidden/stack.json");
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("/proc/forbidden/stack.json"), std::string::npos) << r.output;
}

// The file's camera may name one of the scene's cameras; --camera on the command line wins.
TEST(RenderLensCli, LensFileCameraNamesASceneCamera) {
    const fs::path file = outDir() / "duck-stack.json";
    const fs::path out = outDir() / "duck-stack.png";
    const std::string duck = dataPath("models/Duck/Duck.glb");
    std::ofstream(file) << R"({"scene": ")" << duck << R"(", "camera": {"name": "3"}})";
    const CommandResult bad = runRender("--lenses " + file.string() + kSmall + " -o " + out.string());
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("duck-stack.json: camera '3'"), std::string::npos) << bad.output;
    const CommandResult overridden =
        runRender("--lenses " + file.string() + " --camera 0" + kSmall + " -o " + out.string());
    EXPECT_EQ(overridden.exitCode, 0) << overridden.output;
    std::ofstream(file) << R"({"scene": ")" << duck << R"(", "camera": {"name": 0}})";
    EXPECT_EQ(runRender("--lenses " + file.string() + kSmall + " -o " + out.string()).exitCode, 0);
}

// A session's visibleLayers hide layers outside every lens, as the viewer's layer switches do,
// and --save-lenses keeps them.
TEST(RenderLensCli, VisibleLayersOfASessionHideLayersOutsideTheLenses) {
    const fs::path file = outDir() / "visible-layers.json";
    const fs::path saved = outDir() / "visible-layers-saved.json";
    const fs::path plain = outDir() / "visible-plain.png";
    const fs::path hidden = outDir() / "visible-hidden.png";
    std::ofstream(file) << R"({"scene": "builtin:cube-in-cube", "visibleLayers": "1-"})";
    ASSERT_EQ(runRender(std::string("builtin:cube-in-cube") + kSmall + " -o " + plain.string()).exitCode, 0);
    const CommandResult r = runRender("--lenses " + file.string() + kSmall + " -o " + hidden.string() +
                                      " --save-lenses " + saved.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(readText(saved).find("\"visibleLayers\": \"1-\""), std::string::npos) << readText(saved);
    const mvcl::Framebuffer a = mvcl::readImage(plain), b = mvcl::readImage(hidden);
    int changed = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) changed += a.at(x, y) != b.at(x, y);
    EXPECT_GT(changed, a.width() * a.height() / 4) << "the outer cube, floor and spheres (layer 0) are gone";
}

TEST(RenderLensCli, AFaultyPluginsLensIsDisabledWithAWarningAndTheRenderGoesOn) {
    // fixture-faulty-throws: contribute() throws (tests/lens/fixtures/FixtureFaulty.cpp).
    const fs::path image = outDir() / "faulty-lens.png", saved = outDir() / "faulty-lens.json";
    fs::remove(image);
    fs::remove(saved);
    const CommandResult r = runCommand("MVCL_PLUGIN_PATH=" + quoted(MVCL_FAULTY_PLUGIN_DIR) + " " +
                                       std::string(MVCL_RENDER_EXE) + " --no-progress builtin:cube-in-cube" + kSmall +
                                       " --lens fixture-faulty-throws:center=[0.5,0.5] --lens achromatic:size=[0.3,0.3]" +
                                       " --save-lenses " + quoted(saved.string()) + " -o " + quoted(image.string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("mvcl-render: warning: lens 'fixture-faulty-throws': contribute() failed: fixture failure; "
                            "the lens is disabled"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(image)) << r.output;
    const std::string session = readText(saved);
    EXPECT_NE(session.find("\"type\": \"fixture-faulty-throws\""), std::string::npos) << session;
    EXPECT_NE(session.find("\"type\": \"achromatic\""), std::string::npos) << session;
}
