#include "RenderCommandLine.h"

#include "CommandLineValues.h"

#include <mvcl/core/Error.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <memory>

namespace mvcl::cli {

namespace {

[[noreturn]] void usageError(const std::string &problem) {
    throw Error("command line", problem + " (see mvcl-render --help)");
}

constexpr const char *kUsage = R"(usage: mvcl-render [options] <model.gltf | .glb | .obj | .stl | .ply | builtin:NAME>
       mvcl-render [options] <outer model> <inner model>...   (several files as layers, first = outermost)
       mvcl-render [options] --lenses FILE      (the file names the scene)
       mvcl-render --list-lenses

Scenes:  builtin:cube-in-cube (the default scene of the paper), builtin:onion)";

constexpr const char *kExitCodes = R"(Exit codes: 0 ok, 1 bad input file (scene, layer rules, lens stack, animation), 2 bad arguments
(including --lens, --sweep), 3 image, frames, video, --save-lenses, --save-animation or --convergence-log file not
written, 4 internal error, 130 interrupted (the frames written so far are complete).)";

/// "A-B" (inclusive) or "A": frame numbers from 0.
std::pair<int, int> parseFrameRange(std::string_view text) {
    const std::size_t dash = text.find('-');
    const int first = parseWholeNumber(text.substr(0, dash), 0, 1 << 24);
    const int last = dash == std::string_view::npos ? first : parseWholeNumber(text.substr(dash + 1), 0, 1 << 24);
    if (last < first) throw BadValue("expects A-B with A <= B, got " + quotedValue(text));
    return {first, last};
}

/// The options of mvcl-render bound to `cl`: one table for the parser and --help.
std::unique_ptr<CLI::App> renderApp(RenderCommandLine &cl, std::vector<std::string> &scenes) {
    auto app = std::make_unique<CLI::App>("mvcl-render: ray-trace a layered scene to an image.", "mvcl-render");
    app->formatter(std::make_shared<UsageFormatter>(kUsage));
    app->footer(kExitCodes);
    app->set_help_flag("-h,--help", "this text");
    app->add_option("scene", scenes,
                    "model file or builtin:NAME (or none with --lenses); several model files\n"
                    "are the layers of one scene, the first the outermost")
        ->option_text(" ");

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
    // One option, two meanings told apart by their form: an axis name is the files' up axis,
    // three numbers the camera's up direction.
    app->add_option_function<std::string>(
           "--up",
           [&](const std::string &text) {
               if (text == "y" || text == "z") cl.modelUp = text;
               else cl.up = parseVector3(text);
           },
           "y or z: the up axis of OBJ, STL and PLY files, which do not say (default y);\n"
           "X,Y,Z: the camera's up direction (default 0,1,0)")
        ->type_name("y|z|X,Y,Z")
        ->check(validatorFrom(
            [](const std::string &text) {
                if (text != "y" && text != "z") parseVector3(text);
            },
            ""));
    app->add_option("--unit", cl.unit, "length unit of OBJ, STL and PLY files, which do not say (default m)")
        ->type_name("mm|cm|m|in")
        ->check(CLI::IsMember({"mm", "cm", "m", "in"}));
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
    app->add_option("--view", cl.view,
                    "which view of a --lenses session of several views to render (0, 1, ...),\n"
                    "or 'all': every view side by side in one image")
        ->type_name("N|all");
    app->add_option("--lens", cl.lensSpecs,
                    "one more lens on top, repeatable: TYPE:key=value,... where a key is a\n"
                    "property of the lens or shape, center, size, points, feather, outline,\n"
                    "outlineColor, label, enabled; bracket values with commas, e.g.\n"
                    "--lens layer:shape=ellipse,center=[0.5,0.5],size=[0.4,0.4],layers=1-")
        ->option_text(" SPEC")->allow_extra_args(false);
    app->add_option("--save-lenses", cl.saveLensesFile,
                    "write the effective scene, camera, layer rules and lenses as a lens-stack file")
        ->type_name("FILE");
    app->add_option("--convergence-log", cl.convergenceLogFile,
                    "write a CSV row after every pass: time, samples, rays and the estimated\n"
                    "error (no reference needed; scripts/plot-convergence.py plots it)")
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
    app->add_option("--animate", cl.animationFile,
                    "render an animation file (keyframes of the camera and of the session's lenses)\n"
                    "to numbered images (-o frames/%04d.png) or a video (-o clip.mp4)")
        ->type_name("FILE");
    app->add_option_function<std::string>(
           "--turntable", [&](const std::string &text) { cl.turntableFrames = parseWholeNumber(text, 1, 1 << 20); },
           "animate one turn of the camera about its up axis in N frames (the last\n"
           "frame is one step before the first: the clip loops)")
        ->type_name("N")->check(wholeNumberIn(1, 1 << 20));
    app->add_option("--sweep", cl.sweeps,
                    "animate a lens property from one value to another over the frames,\n"
                    "repeatable: LENS.PROPERTY=FROM:TO, LENS a label or an index (0 = bottom),\n"
                    "e.g. --sweep reveal.distance=0:4")
        ->type_name("SPEC")->allow_extra_args(false);
    app->add_option("--frame-count", cl.frameCount, "frames of a --sweep without --turntable (default 30)")
        ->type_name("N")->check(wholeNumberIn(1, 1 << 20));
    app->add_option_function<std::string>(
           "--frame-rate", [&](const std::string &text) { cl.frameRate = parseFiniteNumber(text); },
           "frames per second of an animation (default: the file's, else 30)")
        ->type_name("FPS")->check(numberBetween(0.0, 1000.0, "in (0, 1000)"));
    app->add_option_function<std::string>(
           "--frames", [&](const std::string &text) { cl.frameRange = parseFrameRange(text); },
           "render only frames A to B of the animation (numbered from 0, as the\n"
           "files are), e.g. to split a long one across machines")
        ->type_name("A-B")->check(validatorFrom([](const std::string &text) { parseFrameRange(text); }, ""));
    app->add_option("--save-animation", cl.saveAnimationFile,
                    "write the animation (of --animate, --turntable, --sweep) as an animation file,\n"
                    "for mvcl-viewer's Play and Record or for editing by hand")
        ->type_name("FILE");
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
    if (scenes.size() > 1)
        for (const std::string &scene : scenes)
            if (scene.starts_with("builtin:"))
                usageError("'" + scene + "' cannot be combined with other scenes (several model files are layers)");
    if (!scenes.empty()) cl.source = scenes.front();
    if (scenes.size() > 1) cl.moreSources.assign(scenes.begin() + 1, scenes.end());
    if (!cl.version && !cl.listLenses && cl.source.empty() && cl.lensFile.empty()) usageError("no scene given");
    if (cl.maxSamplesPerPixel && *cl.maxSamplesPerPixel < cl.samplesPerPixel)
        usageError("--max-spp " + std::to_string(*cl.maxSamplesPerPixel) + " is below --spp " +
                   std::to_string(cl.samplesPerPixel));
    if (cl.eye && cl.target && *cl.eye == *cl.target) usageError("--eye and --target are the same point");
    if (!cl.animationFile.empty() && (cl.turntableFrames || !cl.sweeps.empty()))
        usageError("--animate renders its file; --turntable and --sweep make an animation of their own");
    if (cl.turntableFrames && app->count("--frame-count"))
        usageError("--turntable N sets the frame count already");
    if (isAnimation(cl) && !cl.convergenceLogFile.empty())
        usageError("--convergence-log logs the passes of one image, not of an animation's frames");
    if (!cl.view.empty() && cl.lensFile.empty()) usageError("--view picks a view of the --lenses session");
    if (cl.view == "all")
        for (const char *option : {"--save-lenses", "--convergence-log", "--animate", "--turntable", "--sweep", "--info"})
            if (app->count(option)) usageError(std::string("--view all renders every view into one image; ") + option + " works on one view");
    if (!isAnimation(cl))
        for (const char *option : {"--frames", "--frame-count", "--frame-rate", "--save-animation"})
            if (app->count(option)) usageError(std::string(option) + " needs --animate, --turntable or --sweep");
    return cl;
}

RenderSettings renderSettings(const RenderCommandLine &cl) {
    RenderSettings s;
    s.width = cl.width;
    s.height = cl.height;
    s.samplesPerPixel = cl.samplesPerPixel;
    s.threads = cl.threads;
    s.seed = cl.seed;
    s.skipUnneededStages = !cl.forceAllStages;
    s.previewBudgetSeconds = 0.0; // nothing moves in a batch render
    if (isRefining(cl)) {
        s.sampling = cl.adaptive ? SamplingMode::Adaptive : SamplingMode::Progressive;
        s.minSamplesPerPixel = std::max(2, cl.samplesPerPixel);
        s.maxSamplesPerPixel = cl.maxSamplesPerPixel.value_or(std::max(256, cl.samplesPerPixel));
        s.targetError = cl.targetError.value_or(cl.adaptive ? 0.01f : 0.f);
        s.timeLimitSeconds = cl.timeLimit.value_or(0.0);
    }
    return s;
}

} // namespace mvcl::cli
