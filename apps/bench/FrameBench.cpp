// mvcl-bench frame: the frame's ray rate against the rate of tracing its own rays unshaded.
// The frame is set up as mvcl-render sets it up (ViewSetup: scene, camera, session lenses), so
// the numbers are those of a render a user runs.

#include "FrameBench.h"

#include "BenchSupport.h"
#include "CommandLineValues.h"

#include <mvcl/controller/ViewRequest.h>
#include <mvcl/controller/ViewSetup.h>
#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/TracerQueryLog.h>
#include <mvcl/view/RenderSession.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace mvcl::bench {
namespace {

struct FrameOptions {
    std::string source; ///< empty: the session file's scene, else the default scene
    std::string sessionFile;
    int width = 500;
    int height = 500;
    int samplesPerPixel = 1;
    int threads = 1;
    int repeat = 5;
};

const char *kFrameUsage = "usage: mvcl-bench frame [model | builtin:NAME] [--lenses FILE] [--size WxH] [--spp N]\n"
                          "                        [--threads N] [--repeat R]";

std::optional<FrameOptions> parseFrameOptions(int argc, char **argv) {
    FrameOptions o;
    CLI::App app("mvcl-bench frame: a frame's rays by kind, its ray rate, and the rate of tracing the same rays "
                 "again with no shading (its traversal bound).",
                 "mvcl-bench frame");
    app.formatter(std::make_shared<cli::UsageFormatter>(kFrameUsage));
    app.set_help_flag("-h,--help", "this text");
    app.add_option("model", o.source, "model file or builtin:NAME (default: the --lenses file's scene, else "
                                      "builtin:cube-in-cube)")
        ->option_text(" ");
    app.add_option("--lenses", o.sessionFile, "lens-stack file, as mvcl-render --lenses (its scene unless one is given)")
        ->type_name("FILE");
    cli::addImageSizeOption(app, o.width, o.height, "image size (default 500x500)");
    app.add_option("--spp", o.samplesPerPixel, "samples per pixel (default 1)")->type_name("N")->check(cli::wholeNumberIn(1, 4096));
    app.add_option("--threads", o.threads, "threads for the frame and the replay, 0 = all cores (default 1)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(0, 1024));
    app.add_option("--repeat", o.repeat, "best of R runs of each (default 5)")->type_name("R")->check(cli::wholeNumberIn(1, 1000));
    if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::fputs(app.help().c_str(), stdout);
        return std::nullopt;
    }
    if (o.threads <= 0) o.threads = workerThreadCount();
    return o;
}

} // namespace

int runFrameBench(int argc, char **argv) {
    std::optional<FrameOptions> options;
    try {
        options = parseFrameOptions(argc, argv);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 2;
    }
    if (!options) return 0;
    const FrameOptions &o = *options;
    try {
        LensRegistry registry;
        for (const Error &skipped : registry.loadModules(LensRegistry::defaultSearchPath()))
            std::fprintf(stderr, "mvcl-bench: warning: plugin skipped: %s\n", skipped.what());
        ViewRequest request;
        request.source = o.source.empty() && o.sessionFile.empty() ? "builtin:cube-in-cube" : o.source;
        request.sessionFile = o.sessionFile;
        const ViewSetup setup = ViewSetup::prepare(request, registry);
        const Scene scene = loadScene(setup.source, setup.loadOptions);
        Tracer tracer(scene); // not const: the query log is attached to it

        RenderSettings settings;
        settings.width = o.width;
        settings.height = o.height;
        settings.samplesPerPixel = o.samplesPerPixel;
        settings.threads = o.threads;
        settings.previewBudgetSeconds = 0.0;
        const Camera camera = setup.camera(scene, request, float(o.width) / float(o.height));
        RayPolicy base;
        base.query(RayType::Primary).layerMask = setup.session.visibleLayers;
        // A fresh session per frame: everything is traced anew, as in mvcl-render.
        const auto renderFrame = [&] {
            RenderSession session(tracer);
            session.setSettings(settings);
            session.setCamera(camera);
            session.setBasePolicy(base);
            session.setLensStack(setup.session.lenses);
            return session.renderUntilIdle();
        };

        double frameSeconds = 1e300;
        RenderPassStats frame;
        for (int run = 0; run < o.repeat; ++run) {
            frame = renderFrame();
            frameSeconds = std::min(frameSeconds, frame.milliseconds * 1e-3);
        }
        // Its queries, recorded once, then traced again with no shading on as many threads.
        TracerQueryLog log;
        tracer.setQueryLog(&log);
        renderFrame();
        tracer.setQueryLog(nullptr);
        const std::size_t calls = log.calls();
        double replaySeconds = 1e300;
        std::size_t hits = 0;
        for (int run = 0; run < o.repeat; ++run) {
            std::atomic<std::size_t> found{0};
            const auto start = Clock::now();
            constexpr std::size_t kChunk = 4096;
            parallelFor((calls + kChunk - 1) / kChunk, o.threads, [&](std::size_t chunk) {
                found += log.replay(tracer, chunk * kChunk, std::min(calls, (chunk + 1) * kChunk));
            });
            replaySeconds = std::min(replaySeconds, secondsSince(start));
            hits = found;
        }

        const RayCounters &rays = frame.rays;
        const double total = double(rays.total());
        const double recorded = double(log.closestHitRays() + log.anyHitRays());
        std::printf("scene      %s, %dx%d, %d spp, %d threads, best of %d, on %s\n", scene.name.c_str(), o.width,
                    o.height, o.samplesPerPixel, o.threads, o.repeat, cpuModelName().c_str());
        std::printf("rays       %.3f M: primary %.3f M, shadow %.3f M, reflection %.3f M, refraction %.3f M\n",
                    total * 1e-6, double(rays.primary) * 1e-6, double(rays.shadow) * 1e-6,
                    double(rays.reflection) * 1e-6, double(rays.refraction) * 1e-6);
        std::printf("queries    %.3f M rays in %zu calls (%.3f M closest-hit, %.3f M any-hit; %zu distinct queries; "
                    "%zu hit or occluded)\n",
                    recorded * 1e-6, calls, double(log.closestHitRays()) * 1e-6, double(log.anyHitRays()) * 1e-6,
                    log.distinctQueries(), hits);
        std::printf("frame      %.2f ms, %.2f Mrays/s (rays as counted: a transparent shadow walk is one ray)\n",
                    frameSeconds * 1e3, total / frameSeconds * 1e-6);
        std::printf("unshaded   %.2f ms, %.2f Mrays/s (the same queries replayed: the traversal bound)\n",
                    replaySeconds * 1e3, recorded / replaySeconds * 1e-6);
        // The same rays both times, so the ratio of the rates is that of the times.
        std::printf("ratio      frame rate / traversal bound %.3f (%.0f %% of the frame is spent outside the tracer's "
                    "queries)\n",
                    replaySeconds / frameSeconds, 100.0 * std::max(0.0, 1.0 - replaySeconds / frameSeconds));
        return 0;
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 1;
    }
}

} // namespace mvcl::bench
