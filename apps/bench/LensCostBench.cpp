// mvcl-lens-bench: what lenses cost on a real model. Renders the same view with 0, 1, 3 and 8
// overlapping lenses and reports, per stack, the time to compose the policy map and the time to
// render (best of --repeat), the distinct policies and feathered pixels, and the ratio to the
// lens-free frame. Two kinds of stack are measured: "mixed" cycles layer, achromatic and shadow
// lenses (the cost includes what they change: fewer or more rays), "colour" uses only
// achromatic lenses (the same rays as no lens, so the difference is the lens machinery).
// Finally a lens drag (the top lens of a 3-lens stack moves 8 px per frame; a RenderSession
// re-traces only what changed) and a camera orbit (previews sized to the frame budget).
//
//   mvcl-lens-bench [model | builtin:<name>] [--size WxH] [--spp N] [--threads N] [--repeat R]
//   (exit 2 for bad arguments, 1 when the model does not load)

#include "CommandLineValues.h"

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/RenderSession.h>
#include <mvcl/view/Renderer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace mvcl;
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Options {
    std::string model = "tests/data/models/HRA_Female_Body/HRA_Female_Body.glb";
    int width = 1280;
    int height = 720;
    int spp = 1;
    int threads = 0;
    int repeat = 5;
};

/// Parses the command line; nullopt when help was asked for (and printed). Throws
/// mvcl::Error("command line", ...) for bad arguments.
std::optional<Options> parseOptions(int argc, char **argv) {
    Options o;
    CLI::App app("mvcl-lens-bench: the cost of 0, 1, 3 and 8 overlapping lenses, a lens drag and an orbit.",
                 "mvcl-lens-bench");
    app.formatter(std::make_shared<cli::UsageFormatter>(
        "usage: mvcl-lens-bench [model | builtin:<name>] [--size WxH] [--spp N] [--threads N] [--repeat R]"));
    app.set_help_flag("-h,--help", "this text");
    app.add_option("model", o.model, "model file or builtin:NAME (default the HRA female body)")->option_text(" ");
    cli::addImageSizeOption(app, o.width, o.height, "image size in pixels (default 1280x720)");
    app.add_option("--spp", o.spp, "samples per pixel (default 1)")->type_name("N")->check(cli::wholeNumberIn(1, 65536));
    app.add_option("--threads", o.threads, "render threads, 0 = all cores (default 0)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(0, 1024));
    app.add_option("--repeat", o.repeat, "best of R runs (default 5)")->type_name("R")->check(cli::wholeNumberIn(1, 1000));
    if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::fputs(app.help().c_str(), stdout);
        return std::nullopt;
    }
    return o;
}

/// Lens i of a stack: ellipses around the image centre, offset so that every one overlaps the
/// others in the middle.
std::shared_ptr<Lens> makeLens(const LensRegistry &registry, const std::string &type, int i) {
    std::shared_ptr<Lens> lens = registry.create(type);
    const float angle = 0.785f * float(i);
    LensRegion region = LensRegion::ellipse({0.5f + 0.08f * std::cos(angle), 0.5f + 0.08f * std::sin(angle)},
                                            {0.45f, 0.6f});
    region.setFeather(4.f);
    lens->setRegion(region);
    if (type == "achromatic") lens->setPropertyText("amount", i % 2 ? "0.5" : "1");
    lens->commit();
    return lens;
}

LensStack makeStack(const LensRegistry &registry, int count, bool colourOnly) {
    static const char *const kMixed[] = {"layer", "achromatic", "shadow"};
    LensStack stack;
    for (int i = 0; i < count; ++i) stack.add(makeLens(registry, colourOnly ? "achromatic" : kMixed[i % 3], i));
    return stack;
}

struct Measurement {
    double composeMs = 1e300;
    double renderMs = 1e300;
    size_t policies = 0;
    size_t blendedPixels = 0;
    uint64_t rays = 0;
};

Measurement measure(const LensStack &stack, const Tracer &tracer, const Camera &camera,
                    const RenderSettings &settings, int repeat) {
    Measurement m;
    Framebuffer image;
    for (int r = 0; r < repeat; ++r) {
        const Clock::time_point start = Clock::now();
        const PolicyMap map = stack.compose(RayPolicy{}, settings.width, settings.height);
        m.composeMs = std::min(m.composeMs, millisecondsSince(start));
        const RenderStats stats = Renderer(tracer).render(camera, map, settings, image);
        m.renderMs = std::min(m.renderMs, stats.renderMilliseconds);
        m.policies = map.policies().size();
        m.blendedPixels = map.blendedPixelCount();
        m.rays = stats.rays.total();
    }
    return m;
}

} // namespace

int main(int argc, char **argv) {
    try {
        std::optional<Options> options;
        try {
            options = parseOptions(argc, argv);
        } catch (const Error &e) {
            std::fprintf(stderr, "mvcl-lens-bench: %s\n", e.what());
            return 2;
        }
        if (!options) return 0;
        const Options &o = *options;
        LensRegistry registry;
        for (const Error &e : registry.loadModules(LensRegistry::defaultSearchPath()))
            std::fprintf(stderr, "warning: %s\n", e.what());

        const Scene scene = loadScene(o.model);
        const Tracer tracer(scene);
        const Camera camera = Camera::framing(scene.bounds(), 40.f, float(o.width) / float(o.height));
        RenderSettings settings;
        settings.width = o.width;
        settings.height = o.height;
        settings.samplesPerPixel = o.spp;
        settings.threads = o.threads;

        std::printf("model   %s, %zu triangles, %d layers\n", o.model.c_str(), tracer.buildStats().triangles,
                    scene.layers.count());
        std::printf("view    %dx%d, %d spp, best of %d\n\n", o.width, o.height, o.spp, o.repeat);
        std::printf("%-7s %6s %10s %10s %8s %9s %9s %9s\n", "stack", "lenses", "compose", "render",
                    "ratio", "policies", "blended", "Mrays");
        for (const bool colourOnly : {false, true}) {
            double baseMs = 0.0;
            for (const int count : {0, 1, 3, 8}) {
                const Measurement m = measure(makeStack(registry, count, colourOnly), tracer, camera, settings, o.repeat);
                if (count == 0) baseMs = m.composeMs + m.renderMs;
                std::printf("%-7s %6d %8.2fms %8.1fms %7.3fx %9zu %9zu %9.2f\n", colourOnly ? "colour" : "mixed",
                            count, m.composeMs, m.renderMs, (m.composeMs + m.renderMs) / baseMs, m.policies,
                            m.blendedPixels, double(m.rays) * 1e-6);
            }
        }

        // Lens drag: the top lens of a mixed 3-lens stack moves 8 pixels a frame across the
        // image; after the first full frame each frame re-traces only what changed.
        {
            LensStack stack = makeStack(registry, 3, false);
            const std::shared_ptr<Lens> &top = stack.lens(2);
            RenderSession session(tracer);
            session.setSettings(settings);
            session.setCamera(camera);
            session.setLensStack(stack);
            session.renderPass();
            std::vector<double> frames;
            uint64_t retraced = 0;
            const float step = 8.f / float(o.width);
            for (float x = 0.25f; x <= 0.75f; x += step) {
                LensRegion region = top->region();
                region.setCenter({x, 0.5f});
                top->setRegion(region);
                top->commit();
                const Clock::time_point start = Clock::now();
                session.setLensStack(stack);
                const RenderPassStats pass = session.renderPass();
                frames.push_back(millisecondsSince(start));
                retraced += pass.pixelsTraced;
            }
            std::sort(frames.begin(), frames.end());
            std::printf("\nlens drag: median %.2f ms, worst %.2f ms per frame (%zu frames of 8 px, %.0f pixels re-traced per frame)\n",
                        frames[frames.size() / 2], frames.back(), frames.size(), double(retraced) / double(frames.size()));
        }

        // Camera orbit: each frame moves the camera; the session previews at a resolution sized
        // to its frame budget.
        {
            LensStack stack = makeStack(registry, 3, false);
            RenderSession session(tracer);
            session.setSettings(settings);
            session.setCamera(camera);
            session.setLensStack(stack);
            session.renderPass();
            std::vector<double> frames;
            int divider = 0;
            const glm::vec3 target = camera.target();
            const glm::vec3 offset = camera.eye() - target;
            for (int f = 1; f <= 60; ++f) {
                const float angle = 0.02f * float(f);
                const glm::vec3 eye = target + glm::vec3(std::cos(angle) * offset.x + std::sin(angle) * offset.z, offset.y,
                                                         -std::sin(angle) * offset.x + std::cos(angle) * offset.z);
                const Clock::time_point start = Clock::now();
                session.setCamera(Camera::lookAt(eye, target, camera.up(), camera.verticalFovDegrees()));
                const RenderPassStats pass = session.renderPass();
                frames.push_back(millisecondsSince(start));
                divider = std::max(divider, pass.resolutionDivider);
            }
            std::sort(frames.begin(), frames.end());
            std::printf("camera orbit: median %.2f ms per frame, worst %.2f ms (preview divider up to %d, budget %.1f ms)\n",
                        frames[frames.size() / 2], frames.back(), divider, settings.previewBudgetSeconds * 1e3);
        }
        // Cancellation: an edit while a long refinement pass runs on the background thread;
        // the time from the edit until that pass has returned.
        {
            LensStack stack = makeStack(registry, 3, false);
            RenderSettings refine = settings;
            refine.sampling = SamplingMode::Progressive;
            refine.maxSamplesPerPixel = 1 << 20;
            RenderSession session(tracer);
            session.setSettings(refine);
            session.setCamera(camera);
            session.setLensStack(stack);
            session.start();
            std::vector<double> latencies;
            for (int trial = 0; trial < 20; ++trial) {
                std::this_thread::sleep_for(std::chrono::milliseconds(30 + 7 * trial));
                const uint64_t before = session.passCount();
                const Clock::time_point edit = Clock::now();
                session.setLensStack(stack);
                while (session.passCount() == before) std::this_thread::yield();
                latencies.push_back(millisecondsSince(edit));
            }
            session.stop();
            std::sort(latencies.begin(), latencies.end());
            std::printf("cancel: median %.2f ms, worst %.2f ms from an edit to the end of the pass in flight\n",
                        latencies[latencies.size() / 2], latencies.back());
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-lens-bench: %s\n", e.what());
        return 1;
    }
}
