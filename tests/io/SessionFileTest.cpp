// Session files of several views: today's one-view files read and written as ever (a kept
// version-1 file, byte for byte), version 2 round trips with views, compare stacks, links and
// layout, and errors that name the file and the JSON path.

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/core/Error.h>
#include <mvcl/io/SessionFile.h>
#include <mvcl/lens/LensRegistry.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace mvcl::test {
namespace {

class SessionFileTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        registry = new LensRegistry;
        registry->loadModule(fs::path(MVCL_PLUGIN_BUILD_DIR) / "mvcl-lens-layer.so");
    }
    static void TearDownTestSuite() {
        delete registry;
        registry = nullptr;
    }
    static std::string readText(const fs::path &file) {
        std::ifstream in(file, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }
    static SessionDescription parse(const std::string &text) { return parseSessionJson(text, "s.json", *registry); }

    static const char *twoViews() {
        return R"({"version": 2, "scene": "builtin:cube-in-cube",
            "views": [{"camera": {"eye": [0, 0, 5], "target": [0, 0, 0]}, "visibleLayers": "1-",
                       "lenses": [{"type": "layer", "properties": {"layers": "2"}}],
                       "compare": {"divider": 0.25, "lenses": []}},
                      {"lenses": [{"type": "layer", "label": "b"}, {"type": "layer", "label": "c"}]}],
            "links": [{"views": [1, 0], "camera": true, "layers": true}],
            "layout": "1x2", "focus": 1})";
    }

    static LensRegistry *registry;
};

LensRegistry *SessionFileTest::registry = nullptr;

TEST_F(SessionFileTest, AVersionOneFileOfTodayReadsAsOneViewAndIsWrittenBackByteForByte) {
    const fs::path kept = fs::path(MVCL_TEST_DATA_DIR) / "sessions" / "one-view-v1.json";
    const SessionDescription session = readSessionFile(kept, *registry);
    ASSERT_EQ(session.views.size(), 1u);
    EXPECT_TRUE(session.isSingleView());
    EXPECT_EQ(session.views[0].lenses.size(), 2);
    EXPECT_NE(session.views[0].visibleLayers, kAllLayers);
    EXPECT_EQ(session.view(0), readLensStackFile(kept, *registry));
    const fs::path written = fs::temp_directory_path() / "mvcl-session-one-view.json";
    fs::copy_file(kept, written, fs::copy_options::overwrite_existing); // same folder depth for the scene path
    writeSessionFile(written, session);
    EXPECT_EQ(readText(written), readText(kept));
}

TEST_F(SessionFileTest, VersionTwoRoundTripsViewsCompareLinksLayoutAndFocus) {
    const SessionDescription session = parse(twoViews());
    ASSERT_EQ(session.views.size(), 2u);
    EXPECT_EQ(session.views[0].visibleLayers, ~uint32_t(1));
    ASSERT_TRUE(session.views[0].compare.has_value());
    EXPECT_FLOAT_EQ(session.views[0].compare->divider, 0.25f);
    EXPECT_EQ(session.views[0].compare->lenses.size(), 0);
    EXPECT_FALSE(session.views[1].camera.has_value());
    EXPECT_EQ(session.views[1].lenses.size(), 2);
    ASSERT_EQ(session.links.size(), 1u);
    EXPECT_EQ(session.links[0], (ViewLink{0, 1, true, false, true}));
    EXPECT_EQ(session.layout, ViewLayout::Columns);
    EXPECT_EQ(session.focus, 1);
    EXPECT_FALSE(session.isSingleView());

    const std::string text = sessionJson(session);
    EXPECT_NE(text.find("\"version\": 2"), std::string::npos);
    const SessionDescription again = parse(text);
    EXPECT_EQ(sessionJson(again), text);
    for (int i = 0; i < 2; ++i) EXPECT_EQ(again.view(i), session.view(i)) << i;
    EXPECT_EQ(again.links, session.links);

    // A one-view reader sees the first view.
    EXPECT_EQ(parseLensStackJson(twoViews(), "s.json", *registry), session.view(0));
}

TEST_F(SessionFileTest, OneViewWithCompareOrLinksOrALayoutIsVersionTwo) {
    SessionDescription session = parse(R"({"scene": "builtin:cube-in-cube", "lenses": []})");
    EXPECT_EQ(sessionJson(session).find("\"version\": 2"), std::string::npos);
    session.layout = ViewLayout::Grid;
    EXPECT_NE(sessionJson(session).find("\"version\": 2"), std::string::npos);
    session.layout = ViewLayout::Single;
    session.views[0].compare = CompareDescription{};
    EXPECT_NE(sessionJson(session).find("\"compare\""), std::string::npos);
    EXPECT_TRUE(parse(sessionJson(session)).views[0].compare.has_value());
}

TEST_F(SessionFileTest, BrokenVersionTwoFilesNameTheFileAndThePath) {
    const auto error = [](const std::string &text) { return errorOf([&] { parse(text); }); };
    EXPECT_EQ(error(R"({"version": 2, "camera": {"name": "a"}, "views": [{}]})"),
              "s.json: camera: a version-2 file keeps this in each of its \"views\"");
    EXPECT_EQ(error(R"({"version": 2})"), "s.json: missing \"views\"");
    EXPECT_EQ(error(R"({"version": 2, "views": []})"), "s.json: views: expected an array of 1 to 4 views");
    EXPECT_EQ(error(R"({"version": 2, "views": [{"zoom": 1}]})"),
              "s.json: views[0]: unknown key 'zoom' (known: camera, visibleLayers, lenses, compare)");
    EXPECT_EQ(error(R"({"version": 2, "views": [{}, {"lenses": [{"type": "nope"}]}]})").substr(0, 32),
              "s.json: views[1].lenses[0].type:");
    EXPECT_EQ(error(R"({"version": 2, "views": [{"compare": {"divider": 1.5}}]})"),
              "s.json: views[0].compare.divider: must be in 0..1 (a fraction of the view's width)");
    EXPECT_EQ(error(R"({"version": 2, "views": [{}], "links": [{"views": [0, 1], "camera": true}]})"),
              "s.json: links[0].views[1]: expected a view index 0..0, got 1");
    EXPECT_EQ(error(R"({"version": 2, "views": [{}, {}], "links": [{"views": [1, 1]}]})"),
              "s.json: links[0].views: a view cannot be linked to itself");
    EXPECT_EQ(error(R"({"version": 2, "views": [{}, {}], "links": [{"views": [0, 1]}, {"views": [1, 0]}]})"),
              "s.json: links[1]: views 0 and 1 are linked twice");
    EXPECT_EQ(error(R"({"version": 2, "views": [{}], "layout": "3x3"})"),
              "s.json: layout: unknown layout '3x3' (known: 1, 1x2, 2x1, 2x2)");
    EXPECT_EQ(error(R"({"version": 2, "views": [{}], "focus": 2})"), "s.json: focus: expected a view index 0..0, got 2");
    EXPECT_EQ(error(R"({"version": 3})"), "s.json: version: this build reads versions 1 and 2, got 3");
}

} // namespace
} // namespace mvcl::test
