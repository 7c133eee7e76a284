/// mvcl-lens-conformance — the lens conformance suite on plugin modules, without mvcl's source
/// tree:
///
///     mvcl-lens-conformance PLUGIN... [--gtest_filter=...] [other GoogleTest flags]
///
/// A PLUGIN is a module file (path/to/mvcl-lens-invert.so) or a plugin name ("invert" or
/// "mvcl-lens-invert.so") looked up in the directories of $MVCL_PLUGIN_PATH. With no PLUGIN,
/// every module in $MVCL_PLUGIN_PATH is tested. Each lens type a module registers gets every
/// check as a test named LensConformance/<type>.<check>; commutativity is checked against all
/// the lens types given. Exit status: 0 when every check passes, 1 when one fails (GoogleTest
/// prints the check and the reason), 2 for a module that cannot be found or loaded.

#include <mvcl/core/Error.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/testing/LensConformanceSuite.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr int kUsageError = 2;

void printUsage(std::ostream &out) {
    out << "usage: mvcl-lens-conformance PLUGIN... [--gtest_filter=PATTERN] [GoogleTest flags]\n"
           "  PLUGIN  a lens plugin module (path/to/mvcl-lens-NAME.so), or NAME / mvcl-lens-NAME.so\n"
           "          found in the directories of $MVCL_PLUGIN_PATH (':'-separated). Without\n"
           "          PLUGIN, every module in $MVCL_PLUGIN_PATH is tested.\n"
           "Tests are named LensConformance/<lens type>.<check>; --gtest_list_tests lists them.\n";
}

std::vector<fs::path> pluginPathDirectories() {
    std::vector<fs::path> directories;
    const char *path = std::getenv("MVCL_PLUGIN_PATH");
    if (!path) return directories;
    std::string_view rest(path);
    while (!rest.empty()) {
        const size_t colon = rest.find(':');
        const std::string_view entry = rest.substr(0, colon);
        if (!entry.empty()) directories.emplace_back(entry);
        rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
    }
    return directories;
}

/// The module a PLUGIN argument names; throws mvcl::Error when there is none.
fs::path resolveModule(const std::string &argument, const std::vector<fs::path> &searchPath) {
    if (argument.find('/') != std::string::npos || fs::is_regular_file(argument)) {
        if (!fs::is_regular_file(argument)) throw mvcl::Error(argument, "no such plugin module");
        return argument;
    }
    std::string file = argument;
    if (!file.starts_with("mvcl-lens-")) file = "mvcl-lens-" + file;
    if (!file.ends_with(".so")) file += ".so";
    std::string searched;
    for (const fs::path &directory : searchPath) {
        if (fs::is_regular_file(directory / file)) return directory / file;
        if (!searched.empty()) searched += ':';
        searched += directory.string();
    }
    throw mvcl::Error(argument, searchPath.empty()
                                    ? "not a file, and MVCL_PLUGIN_PATH is not set to look for " + file
                                    : "no " + file + " in MVCL_PLUGIN_PATH (" + searched + ")");
}

} // namespace

int main(int argc, char **argv) {
    ::testing::InitGoogleTest(&argc, argv); // removes the --gtest_* flags it knows
    std::vector<std::string> plugins;
    for (int i = 1; i < argc; ++i) {
        const std::string argument = argv[i];
        if (argument == "-h" || argument == "--help") {
            printUsage(std::cout);
            return 0;
        }
        if (argument.starts_with("-")) {
            std::cerr << "mvcl-lens-conformance: unknown option '" << argument << "'\n";
            printUsage(std::cerr);
            return kUsageError;
        }
        plugins.push_back(argument);
    }

    static mvcl::LensRegistry registry; // lives until the tests have run
    const std::vector<fs::path> searchPath = pluginPathDirectories();
    try {
        if (plugins.empty()) {
            if (searchPath.empty()) {
                std::cerr << "mvcl-lens-conformance: no PLUGIN given and MVCL_PLUGIN_PATH is not set\n";
                printUsage(std::cerr);
                return kUsageError;
            }
            for (const mvcl::Error &error : registry.loadModules(searchPath)) {
                std::cerr << "mvcl-lens-conformance: " << error.what() << '\n';
                return kUsageError;
            }
        }
        for (const std::string &plugin : plugins) registry.loadModule(resolveModule(plugin, searchPath));
    } catch (const mvcl::Error &error) {
        std::cerr << "mvcl-lens-conformance: " << error.what() << '\n';
        return kUsageError;
    }
    if (registry.lensTypes().empty()) {
        std::cerr << "mvcl-lens-conformance: no lens plugin module found in MVCL_PLUGIN_PATH\n";
        return kUsageError;
    }
    for (const std::string &type : registry.lensTypes())
        std::cout << "mvcl-lens-conformance: lens type '" << type << "' from " << registry.origin(type) << '\n';
    mvcl::test::registerLensConformanceTests(registry);
    return RUN_ALL_TESTS() == 0 ? 0 : 1;
}
