#pragma once
// Scripted input for mvcl-viewer (--script FILE): one command per line, '#' starts a comment.
// The whole file is checked before anything runs, so a typo fails at once with its line.
// The syntax is documented in docs/viewer.md.

#include <mvcl/controller/InputEvent.h>

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace mvcl::viewer {

struct ScriptCommand {
    int line = 0;
    std::string name;               ///< e.g. "move", "press", "wait-converged"
    std::vector<std::string> args;  ///< the words after it

    double number(size_t index) const;   ///< throws mvcl::Error naming the line
    int integer(size_t index) const;
    const std::string &word(size_t index) const;
    bool hasWord(const std::string &word) const; ///< e.g. a modifier among the arguments
    /// The modifier words among the arguments (shift, ctrl, alt).
    KeyModifier modifiers() const;
};

class ViewerScript {
public:
    /// Reads and checks `file`; throws mvcl::Error("FILE:LINE", problem).
    static ViewerScript load(const std::filesystem::path &file);
    /// The same from text; errors name `file` (the fuzzer, tests/fuzz/ViewerScriptFuzzer.cpp).
    static ViewerScript parse(std::istream &text, const std::filesystem::path &file);

    bool isEmpty() const { return m_commands.empty(); }
    bool isFinished() const { return m_next >= m_commands.size(); }
    const ScriptCommand &current() const { return m_commands[m_next]; }
    void advance() { ++m_next; }
    const std::filesystem::path &file() const { return m_file; }

    /// Every command and its arguments, for --help and the docs.
    static const char *syntax();

private:
    std::filesystem::path m_file;
    std::vector<ScriptCommand> m_commands;
    size_t m_next = 0;
};

} // namespace mvcl::viewer
