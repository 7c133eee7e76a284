#pragma once
// mvcl-viewer's command line.

#include "ViewerScript.h"

#include <mvcl/controller/ViewRequest.h>
#include <mvcl/view/RenderSettings.h>

#include <filesystem>
#include <optional>
#include <string>

namespace mvcl::viewer {

struct ViewerOptions {
    ViewRequest request;               ///< scene, session file, extra lenses, camera overrides
    int width = 1600;                  ///< window size in screen units
    int height = 900;
    int threads = 0;                   ///< render threads, 0 = all cores
    SamplingMode sampling = SamplingMode::Adaptive;
    int samplesPerPixel = 4;           ///< fixed: per pixel; adaptive: the minimum
    int maxSamplesPerPixel = 256;      ///< progressive and adaptive
    float targetError = 0.005f;        ///< adaptive
    std::optional<ViewerScript> script; ///< --script: events and commands to replay, checked
    std::filesystem::path recovery;    ///< --recovery: where the recovery copy goes
};

/// Parses argv with CLI11 and reads and checks the --script file, before any window system is
/// touched. Returns -1 to go on, or the exit code to end with at once (0 after --help, 2 for a
/// usage error or a bad script line, printed as one line naming the option or FILE:LINE).
int parseViewerOptions(int argc, char **argv, ViewerOptions &options);

} // namespace mvcl::viewer
