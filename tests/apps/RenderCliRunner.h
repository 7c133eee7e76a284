#pragma once
// Runs the apps as a user does, for the CLI and viewer tests: a shell command, exit code and output.

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

namespace mvcl::test {

struct CommandResult {
    int exitCode = -1;
    std::string output; // stdout and stderr together
};

/// Runs a shell command line; stdout and stderr are collected together.
inline CommandResult runCommand(const std::string &commandLine) {
    const std::string cmd = commandLine + " 2>&1";
    CommandResult r;
    FILE *pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    while (std::fgets(buf.data(), int(buf.size()), pipe)) r.output += buf.data();
    const int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

/// `args` go to a shell, so quote paths with quoted().
inline CommandResult runRender(const std::string &args) {
    return runCommand(std::string(MVCL_RENDER_EXE) + " --no-progress " + args);
}

/// A scratch folder shared by the CLI tests.
inline std::filesystem::path outDir() {
    std::filesystem::path p = std::filesystem::temp_directory_path() / "mvcl-cli-test";
    std::filesystem::create_directories(p);
    return p;
}

inline std::string dataPath(const std::string &rel) {
    return (std::filesystem::path(MVCL_TEST_DATA_DIR) / rel).string();
}

/// The path in double quotes for the shell. (Built with append: GCC 12 warns falsely,
/// -Wrestrict, on `"\"" + std::string`.)
inline std::string quoted(const std::string &path) {
    std::string q(1, '"');
    q.append(path).push_back('"');
    return q;
}

} // namespace mvcl::test
