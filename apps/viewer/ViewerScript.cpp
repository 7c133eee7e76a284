#include "ViewerScript.h"

#include <mvcl/core/Error.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace mvcl::viewer {

namespace {

struct Arity {
    size_t minimum, maximum;
};

/// Every command with the number of words it takes.
const std::map<std::string, Arity> &commandTable() {
    static const std::map<std::string, Arity> table = {
        {"move", {2, 2}},          {"press", {1, 4}},           {"release", {1, 4}},
        {"click", {3, 6}},         {"drag", {5, 9}},            {"scroll", {1, 3}},
        {"key", {1, 4}},           {"add-lens", {3, 3}},        {"select", {1, 1}},
        {"set-property", {3, 3}},  {"set-layer", {2, 2}},       {"wait-converged", {0, 0}},
        {"wait-frames", {1, 1}},   {"screenshot", {1, 1}},      {"window-screenshot", {1, 1}},
        {"save-session", {1, 1}},  {"load-session", {1, 1}},    {"open", {1, 32}},
        {"expect-lenses", {1, 1}}, {"bench-begin", {1, 1}},     {"bench-end", {0, 0}},
        {"add-keyframe", {2, 2}},  {"play", {1, 1}},            {"record", {2, 2}},
        {"stop-recording", {0, 0}}, {"write-turntable", {2, 3}}, {"quit", {0, 1}},
        {"recovery", {1, 1}},      {"set-layer-name", {2, 2}},
    };
    return table;
}

[[noreturn]] void fail(const ScriptCommand &c, const std::string &problem) {
    throw Error("script line " + std::to_string(c.line), c.name + ": " + problem);
}

} // namespace

double ScriptCommand::number(size_t index) const {
    const std::string &text = word(index);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        fail(*this, "argument " + std::to_string(index + 1) + " must be a number, got '" + text + "'");
    return value;
}

int ScriptCommand::integer(size_t index) const {
    const double value = number(index);
    if (value != std::floor(value) || std::fabs(value) > 1e9)
        fail(*this, "argument " + std::to_string(index + 1) + " must be a whole number");
    return int(value);
}

const std::string &ScriptCommand::word(size_t index) const {
    if (index >= args.size()) fail(*this, "needs at least " + std::to_string(index + 1) + " arguments");
    return args[index];
}

bool ScriptCommand::hasWord(const std::string &w) const {
    for (const std::string &a : args)
        if (a == w) return true;
    return false;
}

ViewerScript ViewerScript::load(const std::filesystem::path &file) {
    std::ifstream in(file);
    if (!in) throw Error(file.string(), "cannot be read");
    return parse(in, file);
}

ViewerScript ViewerScript::parse(std::istream &in, const std::filesystem::path &file) {
    ViewerScript script;
    script.m_file = file;
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
        if (const size_t hash = text.find('#'); hash != std::string::npos) text.erase(hash);
        std::istringstream words(text);
        ScriptCommand c;
        c.line = line;
        if (!(words >> c.name)) continue;
        for (std::string w; words >> w;) c.args.push_back(w);
        const auto it = commandTable().find(c.name);
        try {
            if (it == commandTable().end()) fail(c, "unknown command (see docs/viewer.md)");
            if (c.args.size() < it->second.minimum || c.args.size() > it->second.maximum)
                fail(c, "takes " + std::to_string(it->second.minimum) + ".." + std::to_string(it->second.maximum) +
                            " arguments, got " + std::to_string(c.args.size()));
        } catch (const Error &e) {
            throw Error(file.string() + ":" + std::to_string(line), e.problem());
        }
        script.m_commands.push_back(std::move(c));
    }
    return script;
}

const char *ViewerScript::syntax() {
    return R"(move X Y                      pointer to framebuffer pixel (X, Y) of the view
press|release BUTTON [MODS]   BUTTON left|middle|right; MODS shift ctrl alt
click BUTTON X Y [MODS]       move, press, release
drag BUTTON X0 Y0 X1 Y1 [N] [MODS]  press at (X0, Y0), N moves (default 8, one per frame), release
scroll STEPS [X Y]            wheel steps (> 0 zooms in) at the pointer or at (X, Y)
key NAME [MODS]               F1 F12 F Home 1..6 PageUp PageDown Delete E D Z Y Escape
add-lens TYPE X Y             a lens of TYPE centred at normalised (X, Y)
select INDEX                  select lens INDEX (-1: none)
set-property INDEX NAME VALUE a property of lens INDEX in its text form
set-layer LAYER visible|hidden
set-layer-name LAYER NAME     rename a layer (one word; the layer panel's field takes any)
recovery restore|discard      answer the start's offer of the last unsaved session
wait-converged                until the render session is idle and its image shown
wait-frames N                 draw N frames
screenshot FILE               the rendered image with lens outlines, no UI
window-screenshot FILE        the whole window, panels included
save-session FILE | load-session FILE | open MODEL
expect-lenses N               fail (exit 1) unless the stack holds N lenses
bench-begin NAME | bench-end  UI frame times between them (median, 95th percentile, worst) on stdout
add-keyframe FILE SECONDS     the camera and the selected lens into animation FILE at SECONDS
write-turntable FILE N [SWEEP] animation FILE: one turn in N frames (0: none), and the sweep
                              LENS.PROPERTY=FROM:TO if given (the panel's Write turntable / sweep)
play FILE                     preview animation FILE on the view (input waits until it ends)
record TARGET FPS             record the view to frames/%04d.png or a video at FPS frames per second
stop-recording                finish the recording
quit [CODE]                   exit with CODE (default 0)
)";
}

} // namespace mvcl::viewer
