#include <mvcl/model/LayerRules.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

using namespace mvcl;

namespace {

std::string errorOf(const auto &fn) {
    try {
        fn();
    } catch (const Error &e) {
        return e.what();
    }
    return "(no error)";
}

std::filesystem::path writeTemp(const std::string &name, const std::string &text) {
    const auto path = std::filesystem::temp_directory_path() / name;
    std::ofstream(path) << text;
    return path;
}

} // namespace

TEST(LayerRulesGlob, Basics) {
    EXPECT_TRUE(globMatch("", ""));
    EXPECT_FALSE(globMatch("", "a"));
    EXPECT_TRUE(globMatch("*", ""));
    EXPECT_TRUE(globMatch("*", "anything"));
    EXPECT_TRUE(globMatch("VH_F_skin", "VH_F_skin"));
    EXPECT_FALSE(globMatch("VH_F_skin", "VH_F_Skin")); // case-sensitive
    EXPECT_TRUE(globMatch("*skin*", "VH_F_skin"));
    EXPECT_TRUE(globMatch("*_spongy_bone_*", "VH_F_femur_spongy_bone_L"));
    EXPECT_FALSE(globMatch("*_spongy_bone_*", "VH_F_femur_compact_bone_L"));
    EXPECT_TRUE(globMatch("?", "x"));
    EXPECT_FALSE(globMatch("?", ""));
    EXPECT_FALSE(globMatch("?", "xy"));
    EXPECT_TRUE(globMatch("a?c", "abc"));
    EXPECT_TRUE(globMatch("a*b*c", "a-b-b-c"));
    EXPECT_FALSE(globMatch("a*b*c", "a-b-b-d"));
    EXPECT_TRUE(globMatch("**a**", "xxaxx"));
    EXPECT_TRUE(globMatch("*.glb", "model.glb"));
    EXPECT_FALSE(globMatch("*.glb", "model.glb.bak"));
    EXPECT_TRUE(globMatch("renal_pyramid_?_*", "renal_pyramid_L_a"));
}

TEST(LayerRulesGlob, NoExponentialBacktracking) {
    const std::string text(5000, 'a');
    const std::string pattern = "*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*b";
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_FALSE(globMatch(pattern, text));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(s, 1.0);
}

TEST(LayerRulesMatch, FirstRuleWinsNodeThenMesh) {
    LayerRules rules;
    rules.add({"*skin*", 0});
    rules.add({"*bone*", 1});
    rules.add({"*", 7});
    EXPECT_EQ(rules.match("VH_F_skin", ""), 0);
    EXPECT_EQ(rules.match("group", "femur_bone"), 1);
    EXPECT_EQ(rules.match("", "anything"), 7);
    EXPECT_EQ(LayerRules().match("a", "b"), std::nullopt);
    EXPECT_TRUE(LayerRules().isEmpty());
    EXPECT_THROW(rules.add({"x", 32}), Error);
    EXPECT_THROW(rules.add({"x", -1}), Error);
}

TEST(LayerRulesFromString, ParsesAndRejects) {
    const LayerRules r = LayerRules::fromString(" *skin*=0 ; *bone*=1;*spongy*=2;");
    ASSERT_EQ(r.rules().size(), 3u);
    EXPECT_EQ(r.rules()[0].pattern, "*skin*");
    EXPECT_EQ(r.rules()[1].layer, 1);
    EXPECT_EQ(r.match("VH_F_femur_spongy", ""), 2);
    EXPECT_TRUE(LayerRules::fromString("").isEmpty());
    EXPECT_NE(errorOf([] { LayerRules::fromString("*skin*"); }).find("no '='"), std::string::npos);
    EXPECT_NE(errorOf([] { LayerRules::fromString("=3"); }).find("empty pattern"), std::string::npos);
    EXPECT_NE(errorOf([] { LayerRules::fromString("a=x"); }).find("not an integer"), std::string::npos);
    EXPECT_NE(errorOf([] { LayerRules::fromString("a=1x"); }).find("not an integer"), std::string::npos);
    EXPECT_NE(errorOf([] { LayerRules::fromString("a="); }).find("not an integer"), std::string::npos);
    EXPECT_NE(errorOf([] { LayerRules::fromString("a=32"); }).find("out of range"), std::string::npos);
    EXPECT_NE(errorOf([] { LayerRules::fromString("a=-1"); }).find("out of range"), std::string::npos);
}

TEST(LayerRulesFromJsonFile, ParsesValidFile) {
    const auto path = writeTemp("mvcl_rules_ok.json",
                                R"({"rules": [{"match": "*skin*", "layer": 0}, {"match": "*bone*", "layer": 1}]})");
    const LayerRules r = LayerRules::fromJsonFile(path);
    ASSERT_EQ(r.rules().size(), 2u);
    EXPECT_EQ(r.match("x_bone", ""), 1);
    std::filesystem::remove(path);
}

TEST(LayerRulesFromJsonFile, ErrorsNameTheFile) {
    const std::pair<const char *, const char *> cases[] = {
        {"{not json", "invalid JSON"},
        {"[]", "top level"},
        {R"({"rules": [], "extra": 1})", "unknown key 'extra'"},
        {R"({})", "missing"},
        {R"({"rules": {}})", "must be an array"},
        {R"({"rules": [3]})", "must be an object"},
        {R"({"rules": [{"match": "*", "layer": 0, "colour": 1}]})", "unknown key 'colour'"},
        {R"({"rules": [{"layer": 0}]})", "\"match\""},
        {R"({"rules": [{"match": "*", "layer": "0"}]})", "\"layer\" must be an integer"},
        {R"({"rules": [{"match": "*", "layer": 1.5}]})", "\"layer\" must be an integer"},
        {R"({"rules": [{"match": "*", "layer": 99}]})", "out of range"},
    };
    int i = 0;
    for (const auto &[text, expected] : cases) {
        const auto path = writeTemp("mvcl_rules_bad_" + std::to_string(i++) + ".json", text);
        const std::string e = errorOf([&] { LayerRules::fromJsonFile(path); });
        EXPECT_NE(e.find(path.string()), std::string::npos) << e;
        EXPECT_NE(e.find(expected), std::string::npos) << text << " → " << e;
        std::filesystem::remove(path);
    }
    const std::string missing = errorOf([] { LayerRules::fromJsonFile("/nonexistent/rules.json"); });
    EXPECT_NE(missing.find("/nonexistent/rules.json"), std::string::npos);
}
