#include "RenderCommandLine.h"

#include "CommandLineValues.h"

#include <mvcl/core/Error.h>

#include <CLI/CLI.hpp>

#include <memory>

namespace mvcl::cli {

namespace {

[[noreturn]] void usageError(const std::string &problem) {
    throw Error("command line", problem + " (see mvcl-render --help)");
}

constexpr const char *kUsage = R"(usage: mvcl-render [options] <model.gltf | model.glb | builtin:NAME>
       mvcl-render [options] --lenses FILE      (the file names the scene)
       mvcl-render --list-lenses

Scenes:  builtin:cube-in-cube (the default scene of the paper), builtin:onion)";

constexpr const char *kExitCodes = R"(Exit codes: 0 ok, 1 bad input file (scene, layer rules, lens stack), 2 bad arguments (including
--lens), 3 image or --save-lenses file not written, 4 internal error.)";

/// The options of mvcl-render bound to `cl`: one table for the parser and --help.
std::unique_ptr<CLI::App> renderApp(RenderCommandLine &cl, std::vector<std::string> &scenes) {
    auto app = std::make_unique<CLI::App>("mvcl-render: ray-trace a layered scene to an image.", "mvcl-render");
    app->formatter(std::make_shared<UsageFormatter>(kUsage));
    app->footer(kExitCodes);
    app->set_help_flag("-h,--help", "this text");
    app->add_option("scene", scenes, "model file or builtin:NAME (or none with --lenses)")->option_text(" ");

    app->add_option("-o,--output", cl.output, "image to write (.png/.jpg/.tif sRGB, .exr linear); default out/<scene>.png")
        ->type_name("FILE");
    addImageSizeOption(*app, cl.width, cl.height, "image size in pixels (default 800x600)");
    app->add_option("--spp", cl.samplesPerPixel, "samples per pixel (default 4); with the options below, the minimum")
        ->type_name("N")->check(wholeNumberIn(1, 65536));
    app->add_flag("--adaptive", cl.adaptive,
                  "adaptive sampling: after --spp samples (at least 2), more only where\n"
                  "the estimated error (or a neighbour's) is above --target-error");
    app->add_option_function<std::string>(
           "--target-error", [&](const std::string &text) { cl.targetError = float(parseFiniteNumber(text)); },
           "stop when every pixel's estimated relative error is at most E\n"
           "(default 0.01 with --adaptive, none otherwise)")
        ->type_name("E")->check(numberBetween(0.0, HUGE_VAL, "> 0"));
    app->add_option_function<std::string>(
           "--time-limit", [&](const std::string &text) { cl.timeLimit = parseFiniteNumber(text); },
           "stop refining after S seconds")
        ->type_name("S")->check(numberBetween(0.0, HUGE_VAL, "> 0 seconds"));
    app->add_option_function<std::string>(
           "--max-spp", [&](const std::string &text) { cl.maxSamplesPerPixel = parseWholeNumber(text, 1, 1 << 20); },
           "no pixel gets more than N samples (default 256 with a budget)\n"
           "(--target-error, --time-limit or --max-spp without --adaptive:\n"
           "progressive sampling, every pixel alike, until the first budget met)")
        ->type_name("N")->check(wholeNumberIn(1, 1 << 20));
    app->add_option("--threads", cl.threads, "render threads, 0 = all cores (default 0; the image does not depend on it)")
        ->type_name("N")->check(wholeNumberIn(0, 1024));
    app->add_option("--seed", cl.seed, "sample jitter seed (default 0)")->type_name("N")->check(wholeNumberIn(0, 1 << 30));
    app->add_option_function<std::string>("--eye", [&](const std::string &text) { cl.eye = parseVector3(text); },
                                          "camera position (world units of the file)")
        ->type_name("X,Y,Z")->check(vector3());
    app->add_option_function<std::string>("--target", [&](const std::string &text) { cl.target = parseVector3(text); },
                                          "point looked at")
        ->type_name("X,Y,Z")->check(vector3());
    app->add_option_function<std::string>("--up", [&](const std::string &text) { cl.up = parseVector3(text); },
                                          "up direction (default 0,1,0)")
        ->type_name("X,Y,Z")->check(vector3());
    app->add_option_function<std::string>("--fov", [&](const std::string &text) { cl.fov = float(parseFiniteNumber(text)); },
                                          "vertical field of view in degrees (default 40)")
        ->type_name("DEG")->check(numberBetween(0.0, 180.0, "in (0, 180) degrees"));
    app->add_option("--camera", cl.camera, "use the file's camera N (index) or with that name")->type_name("N|NAME");
    app->add_option("--layer-rules", cl.layerRulesFile,
                    "JSON layer rules: {\"rules\": [{\"match\": \"*skin*\", \"layer\": 0}, ...]}")
        ->type_name("FILE");
    app->add_option("--layer-rule", cl.layerRules, "inline rules \"glob=layer;glob=layer\" (applied before the file's)")
        ->type_name("RULES");
    app->add_option("--layer-contact", cl.layerContact,
                    "touching layers: an outer layer's hit beats a nearer inner layer's within this distance,\n"
                    "a fraction of the scene's size (1e-4) or in scene units (0.002units); off by default,\n"
                    "--info suggests one")
        ->type_name("D");
    app->add_option("--memory-budget", cl.memoryBudgetMiB,
                    "refuse a model whose meshes and BVH would need more than this many MiB\n"
                    "(estimated before loading; default: half the physical memory)")
        ->check(CLI::PositiveNumber)
        ->type_name("MIB");
    app->add_option("--lenses", cl.lensFile,
                    "lens-stack JSON: lenses, and the scene, camera and layer rules unless\n"
                    "given here (command-line layer rules come first, so they win)")
        ->type_name("FILE");
    app->add_option("--lens", cl.lensSpecs,
                    "one more lens on top, repeatable: TYPE:key=value,... where a key is a\n"
                    "property of the lens or shape, center, size, points, feather, outline,\n"
                    "outlineColor, label, enabled; bracket values with commas, e.g.\n"
                    "--lens layer:shape=ellipse,center=[0.5,0.5],size=[0.4,0.4],layers=1-")
        ->option_text(" SPEC")->allow_extra_args(false);
    app->add_option("--save-lenses", cl.saveLensesFile,
                    "write the effective scene, camera, layer rules and lenses as a lens-stack file")
        ->type_name("FILE");
    app->add_flag("--list-lenses", cl.listLenses, "list the lens types found and their properties, then exit");
    app->add_option("--format", cl.listFormat,
                    "how --list-lenses prints: text (default) or markdown (the property tables of docs/lenses.md)")
        ->check(CLI::IsMember({"text", "markdown"}))
        ->type_name("FORMAT");
    app->add_flag("--info", cl.info, "load and validate only; print meshes, triangles, layers, bounds");
    app->add_flag_callback("--no-default-lights", [&] { cl.defaultLights = false; },
                           "a model file without lights stays unlit (ambient only) instead of\n"
                           "getting the default key and fill lights");
    app->add_flag("--force-all-stages", cl.forceAllStages,
                  "run every integrator stage even where the scene and lenses do not need\n"
                  "it (shadow rays nothing can block, ...), to measure what skipping saves;\n"
                  "the image is the same");
    app->add_flag_callback("--no-progress", [&] { cl.progress = false; }, "no progress bar on stderr");
    app->add_flag("--version", cl.version, "version");
    return app;
}

} // namespace

std::string renderUsage() {
    RenderCommandLine cl;
    std::vector<std::string> scenes;
    return renderApp(cl, scenes)->help();
}

RenderCommandLine parseRenderCommandLine(const std::vector<std::string> &args) {
    RenderCommandLine cl;
    std::vector<std::string> scenes;
    const std::unique_ptr<CLI::App> app = renderApp(cl, scenes);
    cl.help = parseCommandLine(*app, args);
    if (cl.help) return cl;
    if (scenes.size() > 1) usageError("more than one scene given ('" + scenes[0] + "' and '" + scenes[1] + "')");
    if (!scenes.empty()) cl.source = scenes.front();
    if (!cl.version && !cl.listLenses && cl.source.empty() && cl.lensFile.empty()) usageError("no scene given");
    if (cl.maxSamplesPerPixel && *cl.maxSamplesPerPixel < cl.samplesPerPixel)
        usageError("--max-spp " + std::to_string(*cl.maxSamplesPerPixel) + " is below --spp " +
                   std::to_string(cl.samplesPerPixel));
    if (cl.eye && cl.target && *cl.eye == *cl.target) usageError("--eye and --target are the same point");
    return cl;
}

} // namespace mvcl::cli
