#pragma once
// Options of mvcl-render and their parser. Kept apart from main() so the CLI's contract is
// one readable table.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <mvcl/view/RenderSettings.h>

#include <glm/vec3.hpp>

namespace mvcl::cli {

/// Exit codes of mvcl-render (documented in --help and the README).
enum ExitCode : int {
    kExitOk = 0,
    kExitBadInput = 1,  ///< the scene, a layer-rule or a lens-stack file could not be loaded
    kExitUsage = 2,     ///< bad command-line arguments (including a bad --lens spec)
    kExitOutput = 3,    ///< the image, a frame, the video or the --save-lenses file could not be written
    kExitInternal = 4,  ///< a bug: an unexpected exception
    kExitInterrupted = 130, ///< Ctrl+C (SIGINT) or SIGTERM during an animation, as shells report it
};

struct RenderCommandLine {
    std::string source;              ///< model path or builtin:<name>
    std::vector<std::string> moreSources; ///< further model files, layered inside `source` in order
    std::string output;              ///< image path; empty = out/<scene>.png
    int width = 800;
    int height = 600;
    int samplesPerPixel = 4;         ///< fixed sampling; with a budget below, the minimum per pixel
    bool adaptive = false;           ///< --adaptive: samples where the estimated error is high
    std::optional<float> targetError;   ///< --target-error (progressive/adaptive)
    std::optional<double> timeLimit;    ///< --time-limit, seconds
    std::optional<int> maxSamplesPerPixel; ///< --max-spp
    int threads = 0;
    unsigned seed = 0;
    std::optional<glm::vec3> eye;    ///< world space
    std::optional<glm::vec3> target; ///< world space
    std::optional<glm::vec3> up;     ///< camera up (--up X,Y,Z)
    std::string modelUp;             ///< --up y|z: the up axis of files that do not say; empty = y, assumed
    std::string unit;                ///< --unit mm|cm|m|in for files that do not say; empty = m, assumed
    std::optional<float> fov;        ///< vertical, degrees
    std::string camera;              ///< glTF camera index or name; empty = default view
    std::string layerRulesFile;
    std::string layerRules;          ///< "glob=layer;..."
    std::uint64_t memoryBudgetMiB = 0; ///< --memory-budget; 0 = defaultMemoryBudgetBytes()
    std::string layerContact;        ///< --layer-contact, LayerContact::parse() text; empty = the session's or off
    std::string lensFile;            ///< lens-stack JSON (--lenses)
    std::string view;                ///< --view N|all: a view of a session of several; empty = the first
    std::vector<std::string> lensSpecs; ///< "type:key=value,..." (--lens), stacked above the file's
    std::string saveLensesFile;      ///< write the effective stack here (--save-lenses)
    std::string convergenceLogFile;  ///< --convergence-log: a CSV row after every pass
    bool listLenses = false;
    std::string listFormat = "text"; ///< --format of --list-lenses: text | markdown
    bool info = false;
    bool help = false;
    bool version = false;
    bool progress = true;
    bool forceAllStages = false;     ///< run every integrator stage, needed or not (--force-all-stages)
    bool defaultLights = true;       ///< light a file without lights with the default rig (--no-default-lights)
    // Animations: a file, or the shortcuts that make one.
    std::string animationFile;       ///< --animate: animation JSON over the session's lenses
    std::optional<int> turntableFrames; ///< --turntable N: one turn in N frames
    std::vector<std::string> sweeps; ///< --sweep 'LENS.PROPERTY=FROM:TO', repeatable
    std::string saveAnimationFile;   ///< --save-animation: the animation as a file (the viewer plays it)
    int frameCount = 30;             ///< --frame-count: frames of --sweep without --turntable
    std::optional<double> frameRate; ///< --frame-rate: frames per second (the file's, else 30)
    std::optional<std::pair<int, int>> frameRange; ///< --frames A-B, inclusive
};

/// Whether the command line renders an animation rather than one image.
inline bool isAnimation(const RenderCommandLine &cl) {
    return !cl.animationFile.empty() || cl.turntableFrames || !cl.sweeps.empty();
}

/// Whether samples accumulate past --spp: --adaptive, or any of the budgets.
inline bool isRefining(const RenderCommandLine &cl) {
    return cl.adaptive || cl.targetError || cl.timeLimit || cl.maxSamplesPerPixel;
}

/// The render session's settings the command line asks for (size, samples, seed, threads,
/// stages, and the sampling mode and budgets when it refines); nothing moves, so no previews.
RenderSettings renderSettings(const RenderCommandLine &cl);

/// Throws mvcl::Error("command line", ...) on anything malformed.
RenderCommandLine parseRenderCommandLine(const std::vector<std::string> &args);

std::string renderUsage();

} // namespace mvcl::cli
