#include "ViewerScript.h"

#include <mvcl/controller/Document.h>
#include <mvcl/core/Error.h>
#include <mvcl/io/ViewLayout.h>
#include <mvcl/io/ViewLink.h>

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
        {"gizmo-drag", {4, 7}},    {"fit-lens", {2, 3}},        {"follow-pointer", {2, 2}},
        {"layout", {1, 1}},        {"focus-view", {1, 1}},      {"link", {3, 3}},
        {"unlink", {3, 3}},        {"compare", {1, 1}},         {"compare-divider", {1, 1}},
        {"recovery", {1, 1}},      {"set-layer-name", {2, 2}},
    };
    return table;
}

[[noreturn]] void fail(const ScriptCommand &c, const std::string &problem) {
    throw Error("script line " + std::to_string(c.line), c.name + ": " + problem);
}

/// The values of the view commands, checked with the rest of the script before it runs.
void checkValues(const ScriptCommand &c) {
    const auto viewIndex = [&](std::size_t i) {
        const int view = c.integer(i);
        if (view < 0 || view >= Document::kMaxViews)
            fail(c, "view " + c.word(i) + " does not exist (views 0.." + std::to_string(Document::kMaxViews - 1) + ")");
    };
    try {
        if (c.name == "layout") parseViewLayout(c.word(0), "");
        else if (c.name == "link" || c.name == "unlink") parseLinkAspect(c.word(0), "");
    } catch (const Error &e) {
        fail(c, e.problem());
    }
    if (c.name == "focus-view") viewIndex(0);
    if (c.name == "link" || c.name == "unlink") {
        viewIndex(1);
        viewIndex(2);
        if (c.integer(1) == c.integer(2)) fail(c, "a view cannot be linked to itself");
    }
    if (c.name == "compare" && c.word(0) != "on" && c.word(0) != "off") fail(c, "expects on or off, got '" + c.word(0) + "'");
    if (c.name == "compare-divider" && !(c.number(0) >= 0.0 && c.number(0) <= 1.0))
        fail(c, "the divider is a fraction of the view's width, 0..1, got " + c.word(0));
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

KeyModifier ScriptCommand::modifiers() const {
    KeyModifier m = KeyModifier::None;
    if (hasWord("shift")) m = m | KeyModifier::Shift;
    if (hasWord("ctrl")) m = m | KeyModifier::Control;
    if (hasWord("alt")) m = m | KeyModifier::Alt;
    return m;
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
            checkValues(c);
        } catch (const Error &e) {
            throw Error(file.string() + ":" + std::to_string(line), e.problem());
        }
        script.m_commands.push_back(std::move(c));
    }
    return script;
}

const char *ViewerScript::syntax() {
    return R"(move X Y                      pointer to framebuffer pixel (X, Y) of the focused view
press|release BUTTON [MODS]   BUTTON left|middle|right; MODS shift ctrl alt
click BUTTON X Y [MODS]       move, press, release
drag BUTTON X0 Y0 X1 Y1 [N] [MODS]  press at (X0, Y0), N moves (default 8, one per frame), release
scroll STEPS [X Y]            wheel steps (> 0 zooms in) at the pointer or at (X, Y)
key NAME [MODS]               F1 F12 F Home 1..6 PageUp PageDown Delete E D Z Y B P Escape
layout 1|1x2|2x1|2x2          show one view, two side by side, two stacked, or four
focus-view N                  keys, pointer positions and the lens commands go to view N
link|unlink camera|lenses|layers A B   link views A and B two-way (the focused view's copied)
compare on|off                split the focused view: lens stack A left, B right of a divider
compare-divider X             the divider at X (0..1 of the view's width)
add-lens TYPE X Y             a lens of TYPE centred at normalised (X, Y) in the focused view
select INDEX                  select lens INDEX (-1: none)
set-property INDEX NAME VALUE a property of lens INDEX in its text form
set-layer LAYER visible|hidden
set-layer-name LAYER NAME     rename a layer (one word; the layer panel's field takes any)
recovery restore|discard      answer the start's offer of the last unsaved session
wait-converged                until the render session is idle and its image shown
wait-frames N                 draw N frames
screenshot FILE               every shown view as laid out, with lens outlines, no UI
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
gizmo-drag INDEX HANDLE DX DY [MODS]  drag a 3D handle of lens INDEX's first box, sphere, plane
                              or point by (DX, DY) pixels from where it is drawn; HANDLE center
                              +x -x +y -y +z -z rotate-x rotate-y rotate-z radius normal
fit-lens INDEX object|all|layer N  fit lens INDEX's box or sphere to the object under the
                              pointer, everything, or layer N
follow-pointer INDEX on|off   pin lens INDEX's region to the pointer, or unpin it
)";
}

} // namespace mvcl::viewer
