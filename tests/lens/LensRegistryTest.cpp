// LensRegistry: plugin modules found at run time, checked before use, broken ones reported and
// skipped; statically linked plugins registered explicitly. Fixture modules (tests/lens/fixtures)
// are built into MVCL_TEST_PLUGIN_DIR; the in-tree plugins into MVCL_PLUGIN_BUILD_DIR.

#include <mvcl/lens/LensPlugin.h>
#include <mvcl/lens/LensRegistry.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <dlfcn.h>
#include <fstream>
#include <optional>
#include <set>
#include <unistd.h>

// The achromatic plugin's source, compiled into this binary with MVCL_LENS_STATIC_ID=achromatic.
extern "C" const MvclLensPluginEntry *mvcl_lens_plugin_achromatic();

namespace mvcl {
namespace {

namespace fs = std::filesystem;

const fs::path kTestPluginDir = MVCL_TEST_PLUGIN_DIR;
const fs::path kPluginBuildDir = MVCL_PLUGIN_BUILD_DIR;
const std::vector<std::string> kInTreeLenses = {"achromatic", "clip",  "edges", "falsecolor", "layer",
                                                 "magnifier",  "peel",  "section", "shadow",   "xray"};

fs::path fixture(const std::string &name) { return kTestPluginDir / ("mvcl-lens-fixture-" + name + ".so"); }

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

/// Sets (or unsets) MVCL_PLUGIN_PATH for one test and restores it afterwards.
class PluginPathOverride {
public:
    explicit PluginPathOverride(const std::optional<std::string> &value) {
        if (const char *old = std::getenv("MVCL_PLUGIN_PATH")) m_old = old;
        if (value) setenv("MVCL_PLUGIN_PATH", value->c_str(), 1);
        else unsetenv("MVCL_PLUGIN_PATH");
    }
    ~PluginPathOverride() {
        if (m_old) setenv("MVCL_PLUGIN_PATH", m_old->c_str(), 1);
        else unsetenv("MVCL_PLUGIN_PATH");
    }

private:
    std::optional<std::string> m_old;
};

/// A fresh directory under /tmp, removed at the end of the test.
class ScratchDir {
public:
    ScratchDir() : m_path(fs::temp_directory_path() / ("mvcl-registry-test-" + std::to_string(getpid()))) {
        fs::remove_all(m_path);
        fs::create_directories(m_path);
    }
    ~ScratchDir() { fs::remove_all(m_path); }
    const fs::path &path() const { return m_path; }

private:
    fs::path m_path;
};

/// Runs `action`, expects an mvcl::Error whose source is `source` and whose text has every part.
template <class Action>
void expectError(Action action, const std::string &source, const std::vector<std::string> &parts) {
    try {
        action();
        ADD_FAILURE() << "no error; expected one from " << source;
    } catch (const Error &e) {
        EXPECT_EQ(e.source(), source) << e.what();
        for (const std::string &part : parts) EXPECT_TRUE(contains(e.what(), part)) << e.what() << "\nlacks: " << part;
    }
}

// --- entry checks, without any module ---

TEST(LensRegistryTest, EveryEntryFieldIsCheckedWithBothValuesInTheError) {
    const MvclLensPluginEntry valid = *mvcl_lens_plugin_achromatic();
    struct Case {
        const char *what;
        void (*breakIt)(MvclLensPluginEntry &);
        std::vector<std::string> parts;
    };
    const std::string ours = std::to_string(MVCL_LENS_ABI_VERSION);
    const std::string theirs = std::to_string(MVCL_LENS_ABI_VERSION + 1);
    const std::vector<Case> cases = {
        {"abi", [](MvclLensPluginEntry &e) { e.abiVersion += 1; },
         {"built for lens ABI " + theirs + ", this mvcl has " + ours}},
        {"entry size", [](MvclLensPluginEntry &e) { e.entrySize += 8; },
         {"sizeof(MvclLensPluginEntry) " + std::to_string(sizeof(MvclLensPluginEntry) + 8),
          "this mvcl has " + std::to_string(sizeof(MvclLensPluginEntry))}},
        {"lens size", [](MvclLensPluginEntry &e) { e.lensSize += 8; },
         {"sizeof(mvcl::Lens) " + std::to_string(sizeof(Lens) + 8), "this mvcl has " + std::to_string(sizeof(Lens))}},
        {"info size", [](MvclLensPluginEntry &e) { e.infoSize -= 8; },
         {"sizeof(mvcl::LensInfo) " + std::to_string(sizeof(LensInfo) - 8),
          "this mvcl has " + std::to_string(sizeof(LensInfo))}},
        {"contribution size", [](MvclLensPluginEntry &e) { e.contributionSize += 4; },
         {"sizeof(mvcl::LensContribution) " + std::to_string(sizeof(LensContribution) + 4)}},
        {"build tag", [](MvclLensPluginEntry &e) { e.buildTag = "libc++-99/c++20"; },
         {"built with libc++-99/c++20", std::string("this mvcl with ") + MVCL_LENS_BUILD_TAG}},
        {"no build tag", [](MvclLensPluginEntry &e) { e.buildTag = nullptr; }, {"no build tag"}},
        {"no name", [](MvclLensPluginEntry &e) { e.name = nullptr; }, {"no lens type name"}},
        {"empty name", [](MvclLensPluginEntry &e) { e.name = ""; }, {"no lens type name"}},
        {"no factory", [](MvclLensPluginEntry &e) { e.create = nullptr; }, {"no create/destroy"}},
    };
    LensRegistry registry;
    for (const Case &c : cases) {
        SCOPED_TRACE(c.what);
        MvclLensPluginEntry broken = valid;
        c.breakIt(broken);
        expectError([&] { registry.add(&broken, "unit-test.so"); }, "plugin unit-test.so", c.parts);
    }
    expectError([&] { registry.add(nullptr, "unit-test.so"); }, "plugin unit-test.so", {"no plugin description"});
    EXPECT_TRUE(registry.lensTypes().empty()) << "a refused entry must leave the registry unchanged";
}

TEST(LensRegistryTest, StaticallyLinkedPluginIsRegisteredExplicitly) {
    LensRegistry registry;
    EXPECT_FALSE(registry.contains("achromatic"));
    registry.add(mvcl_lens_plugin_achromatic());
    ASSERT_TRUE(registry.contains("achromatic"));
    EXPECT_EQ(registry.origin("achromatic"), "static");

    const std::shared_ptr<Lens> lens = registry.create("achromatic");
    ASSERT_TRUE(lens);
    EXPECT_EQ(lens->typeName(), "achromatic");
    EXPECT_EQ(lens->snapshot()->version, 1u) << "create() commits the lens on its defaults";
    EXPECT_FALSE(lens->hasUncommittedChanges());
    // Its default amount 1 maps pure red to its Rec. 709 luminance in every channel.
    const glm::vec3 grey = lens->snapshot()->contribution.color.matrix * glm::vec3(1.f, 0.f, 0.f);
    EXPECT_NEAR(grey.r, 0.2126f, 1e-6f);
    EXPECT_NEAR(grey.g, 0.2126f, 1e-6f);
    EXPECT_NEAR(grey.b, 0.2126f, 1e-6f);

    expectError([&] { registry.add(mvcl_lens_plugin_achromatic(), "again"); }, "plugin again",
                {"'achromatic' is already registered from static"});
}

TEST(LensRegistryTest, UnknownTypeErrorListsTheKnownTypes) {
    LensRegistry registry;
    expectError([&] { registry.create("achromatc"); }, "lens", {"unknown lens type 'achromatc'", "known: none"});
    registry.add(mvcl_lens_plugin_achromatic());
    registry.loadModule(fixture("good"));
    expectError([&] { registry.create("achromatc"); }, "lens",
                {"unknown lens type 'achromatc' (known: achromatic, fixture-good)"});
    expectError([&] { (void)registry.origin("nope"); }, "lens", {"unknown lens type 'nope'"});
}

// --- modules ---

TEST(LensRegistryTest, EachBrokenModuleGetsAnErrorNamingItsFile) {
    ScratchDir scratch;
    const fs::path notElf = scratch.path() / "mvcl-lens-not-elf.so";
    std::ofstream(notElf) << "this is not a shared object\n";

    LensRegistry registry;
    registry.loadModule(fixture("good"));
    const auto expectRefused = [&](const fs::path &file, const std::vector<std::string> &parts) {
        SCOPED_TRACE(file.string());
        expectError([&] { registry.loadModule(file); }, "plugin " + file.string(), parts);
    };
    expectRefused(fixture("wrong-abi"), {"built for lens ABI " + std::to_string(MVCL_LENS_ABI_VERSION + 1) +
                                         ", this mvcl has " + std::to_string(MVCL_LENS_ABI_VERSION)});
    // A plugin built for the previous ABI (before LensContext) gets the same clear error.
    expectRefused(fixture("old-abi"), {"built for lens ABI 1, this mvcl has " + std::to_string(MVCL_LENS_ABI_VERSION)});
    expectRefused(fixture("wrong-size"), {"sizeof(mvcl::Lens) " + std::to_string(sizeof(Lens) + 8)});
    expectRefused(fixture("no-entry"), {"no entry point 'mvcl_lens_plugin'"});
    expectRefused(notElf, {"cannot be loaded"});
    expectRefused(scratch.path() / "mvcl-lens-missing.so", {"cannot be loaded"});
    // The plugin's own message survives the trip across the module boundary.
    expectRefused(fixture("throwing-create"), {"creating lens 'fixture-throwing-create' failed", "out of lens polish"});
    expectRefused(fixture("misnamed"), {"registers lens type 'fixture-misnamed'", "calls itself 'something-else'"});
    expectRefused(fixture("twin"), {"'fixture-good' is already registered from " + fixture("good").string()});

    EXPECT_EQ(registry.lensTypes(), std::vector<std::string>{"fixture-good"});
    EXPECT_EQ(registry.origin("fixture-good"), fixture("good").string());
}

TEST(LensRegistryTest, LoadModulesSkipsBrokenModulesAndKeepsTheGoodOnes) {
    ScratchDir scratch;
    std::ofstream(scratch.path() / "mvcl-lens-not-elf.so") << "\x7f" "ELF but truncated";
    std::ofstream(scratch.path() / "README.txt") << "not a plugin name: never opened\n";

    LensRegistry registry;
    const std::vector<Error> errors =
        registry.loadModules({kTestPluginDir, scratch.path() / "does-not-exist", scratch.path(), kPluginBuildDir});

    std::set<std::string> failedFiles;
    for (const Error &e : errors) {
        ASSERT_EQ(e.source().rfind("plugin ", 0), 0u) << e.what();
        failedFiles.insert(fs::path(e.source().substr(7)).filename().string());
    }
    const std::set<std::string> expectedFailures = {
        "mvcl-lens-fixture-old-abi.so", "mvcl-lens-fixture-wrong-abi.so", "mvcl-lens-fixture-wrong-size.so", "mvcl-lens-fixture-no-entry.so",
        "mvcl-lens-fixture-throwing-create.so", "mvcl-lens-fixture-misnamed.so", "mvcl-lens-fixture-twin.so",
        "mvcl-lens-not-elf.so"};
    EXPECT_EQ(failedFiles, expectedFailures);
    EXPECT_EQ(errors.size(), expectedFailures.size());

    std::vector<std::string> expectedTypes = kInTreeLenses;
    expectedTypes.push_back("fixture-good");
    std::sort(expectedTypes.begin(), expectedTypes.end());
    EXPECT_EQ(registry.lensTypes(), expectedTypes);
    EXPECT_EQ(registry.origin("fixture-good"), fixture("good").string()) << "the first module found wins";
    for (const std::string &type : registry.lensTypes()) EXPECT_EQ(registry.create(type)->typeName(), type);
}

TEST(LensRegistryTest, TheSameDirectoryOrFileTwiceIsNotADuplicate) {
    LensRegistry registry;
    EXPECT_TRUE(registry.loadModules({kPluginBuildDir, kPluginBuildDir / "." / ".." / "plugins"}).empty());
    EXPECT_TRUE(registry.loadModules({kPluginBuildDir}).empty());
    EXPECT_EQ(registry.lensTypes(), kInTreeLenses);
}

#ifdef MVCL_TEST_OIIO_MODULE
// The image module mvcl-imageio-oiio.so lives with the lens plugins, but is not one: lens loading
// passes it by (it takes only mvcl-lens-*.so), without an error.
TEST(LensRegistryTest, TheImageModuleInThePluginFolderIsNotLoadedAsALens) {
    ASSERT_TRUE(fs::is_regular_file(kPluginBuildDir / "mvcl-imageio-oiio.so"));
    LensRegistry registry;
    EXPECT_TRUE(registry.loadModules({kPluginBuildDir}).empty());
    EXPECT_EQ(registry.lensTypes(), kInTreeLenses);
}
#endif

TEST(LensRegistryTest, ModuleStaysLoadedWhileItsLensesLive) {
    const auto isMapped = [](const fs::path &file) {
        void *handle = dlopen(file.c_str(), RTLD_NOW | RTLD_NOLOAD);
        if (handle) dlclose(handle); // RTLD_NOLOAD still took a reference
        return handle != nullptr;
    };
    ASSERT_FALSE(isMapped(fixture("good")));
    std::shared_ptr<Lens> lens;
    {
        LensRegistry registry;
        registry.loadModule(fixture("good"));
        lens = registry.create("fixture-good");
    }
    ASSERT_TRUE(isMapped(fixture("good"))) << "the registry is gone but its lens still needs the module";
    // The lens's code lives in the module: using it must work.
    lens->setProperty("gain", PropertyValue::real(0.5));
    lens->commit();
    EXPECT_FLOAT_EQ(lens->snapshot()->contribution.color.matrix[0][0], 0.5f);
    lens.reset();
    EXPECT_FALSE(isMapped(fixture("good"))) << "the last lens is gone: the module is closed";
}

// --- search path ---

TEST(LensRegistryTest, DefaultSearchPathFindsTheInTreePluginsFromTheBuildTree) {
    PluginPathOverride noVariable(std::nullopt);
    const std::vector<fs::path> path = LensRegistry::defaultSearchPath();
    ASSERT_EQ(path.size(), 2u);
    EXPECT_TRUE(fs::equivalent(path[0], fs::read_symlink("/proc/self/exe").parent_path()));
    ASSERT_TRUE(fs::exists(path[1])) << path[1];
    EXPECT_TRUE(fs::equivalent(path[1], kPluginBuildDir)) << path[1] << " vs " << kPluginBuildDir;

    LensRegistry registry;
    EXPECT_TRUE(registry.loadModules(path).empty());
    EXPECT_EQ(registry.lensTypes(), kInTreeLenses);
    for (const std::string &type : kInTreeLenses)
        EXPECT_TRUE(fs::equivalent(registry.origin(type), kPluginBuildDir / ("mvcl-lens-" + type + ".so")));
}

TEST(LensRegistryTest, PluginPathVariableComesFirst) {
    PluginPathOverride variable(kTestPluginDir.string() + "::/nonexistent/mvcl-plugins:");
    const std::vector<fs::path> path = LensRegistry::defaultSearchPath();
    ASSERT_EQ(path.size(), 4u) << "empty entries are skipped";
    EXPECT_EQ(path[0], kTestPluginDir);
    EXPECT_EQ(path[1], fs::path("/nonexistent/mvcl-plugins"));

    LensRegistry registry;
    registry.loadModules(path);
    EXPECT_TRUE(registry.contains("fixture-good"));
    EXPECT_TRUE(registry.contains("layer"));
}

} // namespace
} // namespace mvcl
