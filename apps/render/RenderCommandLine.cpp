#include "RenderCommandLine.h"

#include <mvcl/core/Error.h>

#include <charconv>
#include <cmath>
#include <sstream>

namespace mvcl::cli {

namespace {

[[noreturn]] void usageError(const std::string &problem) {
    throw Error("command line", problem + " (see mvcl-render --help)");
}

int parseInt(const std::string &option, const std::string &text, int min, int max) {
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < min || value > max)
        usageError(option + " expects a whole number in " + std::to_string(min) + ".." +
                   std::to_string(max) + ", got '" + text + "'");
    return value;
}

float parseFloat(const std::string &option, const std::string &text) {
    float value = 0.f;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        usageError(option + " expects a finite number, got '" + text + "'");
    return value;
}

glm::vec3 parseVec3(const std::string &option, const std::string &text) {
    glm::vec3 v;
    std::stringstream ss(text);
    std::string part;
    int i = 0;
    while (std::getline(ss, part, ',')) {
        if (i == 3) usageError(option + " expects x,y,z, got '" + text + "'");
        v[i++] = parseFloat(option, part);
    }
    if (i != 3) usageError(option + " expects x,y,z, got '" + text + "'");
    return v;
}

} // namespace

std::string renderUsage() {
    return R"(mvcl-render: ray-trace a layered scene to an image.

usage: mvcl-render [options] <model.gltf | model.glb | builtin:NAME>
       mvcl-render [options] --lenses FILE      (the file names the scene)
       mvcl-render --list-lenses

Scenes:  builtin:cube-in-cube (the default scene of the paper), builtin:onion
Options:
  -o, --output FILE       image to write (.png/.jpg/.tif sRGB, .exr linear); default out/<scene>.png
      --size WxH          image size in pixels (default 800x600)
      --spp N             samples per pixel (default 4); with the options below, the minimum
      --adaptive          adaptive sampling: after --spp samples (at least 2), more only where
                          the estimated error (or a neighbour's) is above --target-error
      --target-error E    stop when every pixel's estimated relative error is at most E
                          (default 0.01 with --adaptive, none otherwise)
      --time-limit S      stop refining after S seconds
      --max-spp N         no pixel gets more than N samples (default 256 with a budget)
                          (--target-error, --time-limit or --max-spp without --adaptive:
                          progressive sampling, every pixel alike, until the first budget met)
      --threads N         render threads, 0 = all cores (default 0; the image does not depend on it)
      --seed N            sample jitter seed (default 0)
      --eye X,Y,Z         camera position (world units of the file)
      --target X,Y,Z      point looked at
      --up X,Y,Z          up direction (default 0,1,0)
      --fov DEG           vertical field of view in degrees (default 40)
      --camera N|NAME     use the file's camera N (index) or with that name
      --layer-rules FILE  JSON layer rules: {"rules": [{"match": "*skin*", "layer": 0}, ...]}
      --layer-rule RULES  inline rules "glob=layer;glob=layer" (applied before the file's)
      --lenses FILE       lens-stack JSON: lenses, and the scene, camera and layer rules unless
                          given here (command-line layer rules come first, so they win)
      --lens SPEC         one more lens on top, repeatable: TYPE:key=value,... where a key is a
                          property of the lens or shape, center, size, points, feather, outline,
                          outlineColor, label, enabled; bracket values with commas, e.g.
                          --lens layer:shape=ellipse,center=[0.5,0.5],size=[0.4,0.4],layers=1-
      --save-lenses FILE  write the effective scene, camera, layer rules and lenses as a lens-stack file
      --list-lenses       list the lens types found and their properties, then exit
      --info              load and validate only; print meshes, triangles, layers, bounds
      --no-default-lights a model file without lights stays unlit (ambient only) instead of
                          getting the default key and fill lights
      --force-all-stages  run every integrator stage even where the scene and lenses do not need
                          it (shadow rays nothing can block, ...), to measure what skipping saves;
                          the image is the same
      --no-progress       no progress bar on stderr
  -h, --help              this text
      --version           version
Exit codes: 0 ok, 1 bad input file (scene, layer rules, lens stack), 2 bad arguments (including
--lens), 3 image or --save-lenses file not written, 4 internal error.
)";
}

RenderCommandLine parseRenderCommandLine(const std::vector<std::string> &args) {
    RenderCommandLine cl;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string &a = args[i];
        auto value = [&]() -> const std::string & {
            if (i + 1 >= args.size()) usageError(a + " needs a value");
            return args[++i];
        };
        if (a == "-h" || a == "--help") cl.help = true;
        else if (a == "--version") cl.version = true;
        else if (a == "--info") cl.info = true;
        else if (a == "--no-progress") cl.progress = false;
        else if (a == "--force-all-stages") cl.forceAllStages = true;
        else if (a == "--no-default-lights") cl.defaultLights = false;
        else if (a == "-o" || a == "--output") cl.output = value();
        else if (a == "--size") {
            const std::string &s = value();
            const auto x = s.find('x');
            if (x == std::string::npos) usageError("--size expects WxH, got '" + s + "'");
            cl.width = parseInt("--size", s.substr(0, x), 1, 16384);
            cl.height = parseInt("--size", s.substr(x + 1), 1, 16384);
        } else if (a == "--spp") cl.samplesPerPixel = parseInt(a, value(), 1, 65536);
        else if (a == "--adaptive") cl.adaptive = true;
        else if (a == "--target-error") {
            cl.targetError = parseFloat(a, value());
            if (*cl.targetError <= 0.f) usageError("--target-error must be > 0");
        } else if (a == "--time-limit") {
            cl.timeLimit = parseFloat(a, value());
            if (*cl.timeLimit <= 0.0) usageError("--time-limit must be > 0 seconds");
        } else if (a == "--max-spp") cl.maxSamplesPerPixel = parseInt(a, value(), 1, 1 << 20);
        else if (a == "--threads") cl.threads = parseInt(a, value(), 0, 1024);
        else if (a == "--seed") cl.seed = unsigned(parseInt(a, value(), 0, 1 << 30));
        else if (a == "--eye") cl.eye = parseVec3(a, value());
        else if (a == "--target") cl.target = parseVec3(a, value());
        else if (a == "--up") cl.up = parseVec3(a, value());
        else if (a == "--fov") {
            cl.fov = parseFloat(a, value());
            if (*cl.fov <= 0.f || *cl.fov >= 180.f) usageError("--fov must be in (0, 180) degrees");
        } else if (a == "--camera") cl.camera = value();
        else if (a == "--layer-rules") cl.layerRulesFile = value();
        else if (a == "--layer-rule") cl.layerRules = value();
        else if (a == "--lenses") cl.lensFile = value();
        else if (a == "--lens") cl.lensSpecs.push_back(value());
        else if (a == "--save-lenses") cl.saveLensesFile = value();
        else if (a == "--list-lenses") cl.listLenses = true;
        else if (!a.empty() && a[0] == '-') usageError("unknown option '" + a + "'");
        else if (cl.source.empty()) cl.source = a;
        else usageError("more than one scene given ('" + cl.source + "' and '" + a + "')");
    }
    if (!cl.help && !cl.version && !cl.listLenses && cl.source.empty() && cl.lensFile.empty())
        usageError("no scene given");
    if (cl.maxSamplesPerPixel && *cl.maxSamplesPerPixel < cl.samplesPerPixel)
        usageError("--max-spp " + std::to_string(*cl.maxSamplesPerPixel) + " is below --spp " +
                   std::to_string(cl.samplesPerPixel));
    if (cl.eye && cl.target && *cl.eye == *cl.target) usageError("--eye and --target are the same point");
    return cl;
}

} // namespace mvcl::cli
