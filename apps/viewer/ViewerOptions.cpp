#include "ViewerOptions.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/LayerRules.h>
#include <mvcl/model/MeshFileLoader.h>

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace mvcl::viewer {

int parseViewerOptions(int argc, char **argv, ViewerOptions &options) {
    CLI::App app{"mvcl-viewer: open a layered model, stack and drag lenses over it, look inside in real time.\n"
                 "Press F1 in the window for every mouse and key binding.",
                 "mvcl-viewer"};
    std::string size, layerRule, up, unit;
    std::vector<std::string> scenes;
    std::uint64_t memoryBudgetMiB = 0;
    std::filesystem::path script;
    app.add_option("scene", scenes,
                   "model file (.gltf .glb .obj .stl .ply) or builtin:NAME (default: the session's scene);\n"
                   "several model files are the layers of one scene, the first the outermost");
    app.add_option("--lenses,--session", options.request.sessionFile, "session (lens-stack) file to open");
    app.add_option("--lens", options.request.lensSpecs, "one more lens on top: TYPE:key=value,... (repeatable)");
    app.add_option("--layer-rule", layerRule, "inline layer rules \"glob=layer;...\" (win over the session's)");
    app.add_option("--up", up, "up axis of OBJ, STL and PLY files, which do not say (default y)")
        ->check(CLI::IsMember({"y", "z"}));
    app.add_option("--unit", unit, "length unit of OBJ, STL and PLY files (default m)")
        ->check(CLI::IsMember({"mm", "cm", "m", "in"}));
    app.add_option("--memory-budget", memoryBudgetMiB,
                   "refuse a model whose meshes and BVH would need more MiB (default: the session's, else half the memory)")
        ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 40));
    app.add_option("--size", size, "window size WxH in screen units (default 1600x900)");
    app.add_option("--threads", options.threads, "render threads, 0 = all cores")->check(CLI::Range(0, 1024));
    const std::map<std::string, SamplingMode> modes = {
        {"fixed", SamplingMode::Fixed}, {"progressive", SamplingMode::Progressive}, {"adaptive", SamplingMode::Adaptive}};
    app.add_option("--sampling", options.sampling, "fixed | progressive | adaptive (default adaptive)")
        ->transform(CLI::CheckedTransformer(modes, CLI::ignore_case));
    app.add_option("--spp", options.samplesPerPixel, "samples per pixel (fixed), the minimum (adaptive); default 4")
        ->check(CLI::Range(1, 65536));
    app.add_option("--max-spp", options.maxSamplesPerPixel, "most samples per pixel (progressive, adaptive); default 256")
        ->check(CLI::Range(1, 1 << 20));
    app.add_option("--target-error", options.targetError, "adaptive: estimated relative error to reach; default 0.005")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--script", script, "replay events and commands from FILE (see docs/viewer.md)")
        ->check(CLI::ExistingFile);
    app.add_option("--recovery", options.recovery, "where the recovery copy of the session goes");
    try {
        app.parse(argc, argv);
        if (!size.empty()) {
            int w = 0, h = 0;
            char x = 0;
            if (std::sscanf(size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 64 || h < 64 || w > 16384 ||
                h > 16384)
                throw CLI::ValidationError("--size", "expects WxH (64..16384 each), got '" + size + "'");
            options.width = w;
            options.height = h;
        }
        if (!layerRule.empty()) options.request.loadOptions.layerRules = LayerRules::fromString(layerRule);
        if (!scenes.empty()) {
            options.request.source = scenes.front();
            options.request.moreSources.assign(scenes.begin() + 1, scenes.end());
        }
        if (!up.empty()) options.request.loadOptions.upAxis = upAxisFromName(up);
        if (!unit.empty()) options.request.loadOptions.unit = lengthUnitFromName(unit);
        options.request.loadOptions.memoryBudgetBytes = memoryBudgetMiB << 20;
    } catch (const CLI::CallForHelp &) {
        std::fputs(app.help().c_str(), stdout);
        return 0;
    } catch (const CLI::ParseError &e) {
        std::fprintf(stderr, "mvcl-viewer: command line: %s (see mvcl-viewer --help)\n", e.what());
        return 2;
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-viewer: command line: --layer-rule: %s\n", e.problem().c_str());
        return 2;
    }
    try {
        if (!script.empty()) options.script = ViewerScript::load(script);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-viewer: %s\n", e.what());
        return 2;
    }
    return -1;
}

} // namespace mvcl::viewer
