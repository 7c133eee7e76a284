// mvcl-bench pov: the scene mvcl-render would render, as a POV-Ray 3.7 scene with the same camera,
// lights, materials and trace depth (the mapping is in PovScene.h), for whole-frame comparisons
// with POV-Ray (scripts/frame-vs-povray.sh, docs/benchmarks.md). mvcl-bench image-diff: the mean
// and largest difference of two 8-bit images, to show that both renderers drew the same picture.

#include "PovBench.h"

#include "CommandLineValues.h"
#include "ImageError.h"
#include "PovScene.h"

#include <mvcl/controller/ViewCoordinates.h>
#include <mvcl/controller/ViewSetup.h>
#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/tracer/RayPolicy.h>
#include <mvcl/view/ImageIO.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace mvcl::bench {
namespace {

struct PovOptions {
    std::string scene;
    std::string output; ///< empty: out/<scene>.pov
    int width = 800;
    int height = 600;
    ViewRequest request; ///< camera choices, as mvcl-render's command line makes them
};

const char *kPovUsage =
    "usage: mvcl-bench pov SCENE [--size WxH] [-o FILE.pov]\n"
    "                      [--fov DEG] [--eye X,Y,Z] [--target X,Y,Z] [--up X,Y,Z] [--camera N|NAME]";

const char *kPovFooter =
    "SCENE is loaded as mvcl-render loads it (layer inference, the default key and fill lights when a\n"
    "model file has none) and framed as mvcl-render frames it for a WxH image. Written: triangle\n"
    "meshes as mesh2 in world space (with their vertex normals), spheres, planes, point lights and\n"
    "directional ones (parallel lights far away), the ambient light and background, the camera\n"
    "(our vertical field of view as POV's horizontal angle, right-handed), each material's Phong and\n"
    "Whitted terms (ambient, diffuse colour, specular Ks with roughness 1/Ps, reflection, transmit\n"
    "with ior and Fresnel reflection, a see-through surface's highlight as Ks*(1-T)), max_trace_level\n"
    "= bounces + 1, adc_bailout 0, assumed_gamma 1. Not converted: textures (factors only) and alpha\n"
    "masks; the file's header comment lists these and whatever else it approximates.\n"
    "Prints on stdout the mvcl-render camera options of the same view (--eye --target --up --fov,\n"
    "world units), and a summary on stderr. Both renderers, one ray per pixel centre, at 800x600:\n"
    "  mvcl-render SCENE --size 800x600 --spp 1 $(mvcl-bench pov SCENE --size 800x600 -o scene.pov)\n"
    "  povray +Iscene.pov +W800 +H600 -A -J0 +FN -D -P File_Gamma=sRGB\n"
    "scripts/frame-vs-povray.sh times both on three scenes (docs/benchmarks.md).";

/// The shortest text that reads back as the same float (what mvcl-render's parser reads).
std::string shortest(float v) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, v);
    return std::string(text, result.ptr);
}

std::string commaSeparated(const glm::vec3 &v) { return shortest(v.x) + "," + shortest(v.y) + "," + shortest(v.z); }

std::optional<PovOptions> parsePovOptions(int argc, char **argv) {
    PovOptions o;
    CLI::App app("mvcl-bench pov: a scene as POV-Ray 3.7 sees it, with mvcl-render's camera, lights, materials "
                 "and trace depth.",
                 "mvcl-bench pov");
    app.formatter(std::make_shared<cli::UsageFormatter>(kPovUsage));
    app.footer(kPovFooter);
    app.set_help_flag("-h,--help", "this text");
    app.add_option("scene", o.scene, "model file (.glb, .gltf) or builtin:NAME")->option_text(" ")->required();
    cli::addImageSizeOption(app, o.width, o.height, "the image the camera is framed for (default 800x600)");
    app.add_option("-o,--output", o.output, "POV-Ray scene to write (default out/<scene>.pov)")->type_name("FILE");
    ViewRequest &r = o.request;
    app.add_option_function<std::string>(
           "--fov", [&](const std::string &text) { r.verticalFovDegrees = float(cli::parseFiniteNumber(text)); },
           "vertical field of view in degrees (default 40), as mvcl-render's")
        ->type_name("DEG")
        ->check(cli::numberBetween(0.0, 180.0, "in (0, 180) degrees"));
    app.add_option_function<std::string>("--eye", [&](const std::string &text) { r.eye = cli::parseVector3(text); },
                                         "camera position (world units of the file)")
        ->type_name("X,Y,Z")
        ->check(cli::vector3());
    app.add_option_function<std::string>("--target",
                                         [&](const std::string &text) { r.target = cli::parseVector3(text); },
                                         "point looked at")
        ->type_name("X,Y,Z")
        ->check(cli::vector3());
    app.add_option_function<std::string>("--up", [&](const std::string &text) { r.up = cli::parseVector3(text); },
                                         "up direction (default 0,1,0)")
        ->type_name("X,Y,Z")
        ->check(cli::vector3());
    app.add_option("--camera", r.sceneCamera, "the file's camera N (index) or with that name")->type_name("N|NAME");
    if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::fputs(app.help().c_str(), stdout);
        return std::nullopt;
    }
    if (r.eye && r.target && *r.eye == *r.target)
        throw Error("command line", "--eye and --target are the same point (see mvcl-bench pov --help)");
    r.source = o.scene;
    return o;
}

std::string sceneStem(const std::string &source) {
    if (source.rfind("builtin:", 0) == 0) return source.substr(8);
    return std::filesystem::path(source).stem().string();
}

} // namespace

int runPovExport(int argc, char **argv) {
    std::optional<PovOptions> options;
    try {
        options = parsePovOptions(argc, argv);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 2;
    }
    if (!options) return 0;
    const PovOptions &o = *options;
    try {
        // What mvcl-render does with the same command line: prepare the view, load the scene with
        // its options, take the camera it would take.
        const LensRegistry registry; // no lenses are asked for, so no plugins are needed
        const ViewSetup setup = ViewSetup::prepare(o.request, registry);
        const Scene scene = loadScene(setup.source, setup.loadOptions);
        const float aspect = float(o.width) / float(o.height);
        const Camera framed = setup.camera(scene, o.request, aspect);

        // The camera as mvcl-render options; the POV camera is the one mvcl-render makes of them,
        // so both renderers get the same view to the last bit of the float conversions.
        const ViewCoordinates coordinates({o.width, o.height}, scene);
        const std::string renderArgs = "--eye " + commaSeparated(coordinates.worldFromScene(framed.eye())) +
                                       " --target " + commaSeparated(coordinates.worldFromScene(framed.target())) +
                                       " --up " + commaSeparated(framed.up()) + " --fov " +
                                       shortest(framed.verticalFovDegrees());
        ViewRequest asRendered = o.request;
        asRendered.sceneCamera.clear();
        asRendered.eye = coordinates.worldFromScene(framed.eye());
        asRendered.target = coordinates.worldFromScene(framed.target());
        asRendered.up = framed.up();
        asRendered.verticalFovDegrees = framed.verticalFovDegrees();
        const Camera camera = setup.camera(scene, asRendered, aspect);

        PovSceneOptions povOptions;
        povOptions.source = o.scene;
        povOptions.width = o.width;
        povOptions.height = o.height;
        povOptions.maxDepth = ShadingPolicy{}.maxDepth; // what mvcl-render's base policy traces
        povOptions.renderArgs = renderArgs;
        const std::filesystem::path output = o.output.empty() ? "out/" + sceneStem(o.scene) + ".pov" : o.output;
        if (output.has_parent_path()) {
            std::error_code ec;
            std::filesystem::create_directories(output.parent_path(), ec);
        }
        std::ofstream file(output, std::ios::binary);
        if (!file) throw Error(output.string(), "cannot write");
        const PovSceneSummary summary = writePovScene(file, scene, camera, povOptions);
        file.close();
        if (!file) throw Error(output.string(), "write failed");

        std::printf("%s\n", renderArgs.c_str());
        std::fprintf(stderr,
                     "mvcl-bench pov: wrote %s: %zu triangles in %zu mesh2, %zu spheres, %zu planes, %zu lights, "
                     "%zu materials, max_trace_level %d\n",
                     output.string().c_str(), summary.triangles, summary.meshes, summary.spheres, summary.planes,
                     summary.lights, summary.materials, povOptions.maxDepth + 1);
        for (const std::string &note : summary.notes) std::fprintf(stderr, "  approximated: %s\n", note.c_str());
        return 0;
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return e.source() == "command line" ? 2 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 1;
    }
}

int runImageDiff(int argc, char **argv) {
    std::string first, second, diffImage;
    int threshold = 8;
    CLI::App app("mvcl-bench image-diff: how far apart two images of the same size are, in 8-bit sRGB levels.",
                 "mvcl-bench image-diff");
    app.formatter(std::make_shared<cli::UsageFormatter>(
        "usage: mvcl-bench image-diff A.png B.png [--threshold LEVELS] [--write-diff FILE.png]"));
    app.footer("Prints: mean |A-B| over pixels and channels, the largest, and the share of pixels with a\n"
               "channel more than LEVELS apart (exit 1 if an image cannot be read or the sizes differ).");
    app.set_help_flag("-h,--help", "this text");
    app.add_option("a", first, "first image")->option_text(" ")->required();
    app.add_option("b", second, "second image")->option_text(" ")->required();
    app.add_option("--threshold", threshold, "count pixels more than LEVELS apart (default 8)")
        ->type_name("LEVELS")
        ->check(cli::wholeNumberIn(0, 255));
    app.add_option("--write-diff", diffImage, "write |A-B| per channel, 8 times brighter, as an image")
        ->type_name("FILE");
    try {
        if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
            std::fputs(app.help().c_str(), stdout);
            return 0;
        }
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 2;
    }
    try {
        const Framebuffer a = readImage(first);
        const Framebuffer b = readImage(second);
        const LevelDifference d = levelDifference(a, b, threshold);
        std::printf("mean %.4f levels, max %d levels, %.4f %% of pixels more than %d levels apart\n", d.mean, d.max,
                    100.0 * d.shareAbove, d.threshold);
        if (!diffImage.empty()) {
            Framebuffer diff(a.width(), a.height());
            for (std::size_t i = 0; i < diff.pixels().size(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const float shown = std::min(
                        1.f, 8.f * std::abs(linearToSrgb(a.pixels()[i][c]) - linearToSrgb(b.pixels()[i][c])));
                    diff.pixels()[i][c] = srgbToLinear(shown);
                }
            writeImage(diffImage, diff);
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 1;
    }
}

} // namespace mvcl::bench
