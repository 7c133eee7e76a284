#pragma once
// Options of mvcl-render and their parser. Kept apart from main() so the CLI's contract is
// one readable table.

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace mvcl::cli {

/// Exit codes of mvcl-render (documented in --help and the README).
enum ExitCode : int {
    kExitOk = 0,
    kExitBadInput = 1,  ///< the scene or a layer-rule file could not be loaded
    kExitUsage = 2,     ///< bad command-line arguments
    kExitOutput = 3,    ///< the image could not be written
    kExitInternal = 4,  ///< a bug: an unexpected exception
};

struct RenderCommandLine {
    std::string source;              ///< model path or builtin:<name>
    std::string output;              ///< image path; empty = out/<scene>.png
    int width = 800;
    int height = 600;
    int samplesPerPixel = 4;
    int threads = 0;
    unsigned seed = 0;
    std::optional<glm::vec3> eye;    ///< world space
    std::optional<glm::vec3> target; ///< world space
    std::optional<glm::vec3> up;
    std::optional<float> fov;        ///< vertical, degrees
    std::string camera;              ///< glTF camera index or name; empty = default view
    std::string layerRulesFile;
    std::string layerRules;          ///< "glob=layer;..."
    bool info = false;
    bool help = false;
    bool version = false;
    bool progress = true;
};

/// Throws mvcl::Error("command line", ...) on anything malformed.
RenderCommandLine parseRenderCommandLine(const std::vector<std::string> &args);

std::string renderUsage();

} // namespace mvcl::cli
