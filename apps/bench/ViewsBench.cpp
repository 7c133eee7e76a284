#include "ViewsBench.h"

#include "CommandLineValues.h"

#include <mvcl/controller/Controller.h>
#include <mvcl/controller/Document.h>
#include <mvcl/core/Error.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <time.h>
#include <unistd.h>
#include <vector>

namespace mvcl::bench {

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
    std::string model = "tests/data/models/HRA_Female_Body/HRA_Female_Body.glb";
    int width = 1280;
    int height = 720;
    int threads = 0;
    int frames = 60;
};

std::optional<Options> parseOptions(int argc, char **argv) {
    Options o;
    CLI::App app("mvcl-bench views: two views of one model: memory, a lens drag beside an idle view, a linked orbit.",
                 "mvcl-bench views");
    app.formatter(std::make_shared<cli::UsageFormatter>(
        "usage: mvcl-bench views [model | builtin:<name>] [--size WxH] [--threads N] [--frames N]"));
    app.set_help_flag("-h,--help", "this text");
    app.add_option("model", o.model, "model file or builtin:NAME (default the HRA female body)")->option_text(" ");
    cli::addImageSizeOption(app, o.width, o.height, "size of each view in pixels (default 1280x720)");
    app.add_option("--threads", o.threads, "render threads, 0 = all cores (default 0)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(0, 1024));
    app.add_option("--frames", o.frames, "UI frames per measurement (default 60)")->type_name("N")->check(cli::wholeNumberIn(4, 100000));
    if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::fputs(app.help().c_str(), stdout);
        return std::nullopt;
    }
    return o;
}

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Resident memory of the process in MiB.
double residentMiB() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

/// CPU time of the whole process (every thread), in seconds: steadier than the wall clock on a
/// machine shared with other work.
double processCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

/// One UI frame: the input, then every view's pass (an idle view returns at once).
double uiFrame(Document &document, const std::function<void()> &input) {
    const Clock::time_point start = Clock::now();
    input();
    for (int i = 0; i < document.viewCount(); ++i) document.view(i).renderSession().renderPass();
    return millisecondsSince(start);
}

void renderUntilIdle(Document &document) {
    for (int i = 0; i < document.viewCount(); ++i) document.view(i).renderSession().renderUntilIdle();
}

/// A left drag in view `view` (views side by side) from `from` by `step` pixels a frame.
std::vector<double> dragFrames(Document &document, int view, const glm::vec2 &from, const glm::vec2 &step, int frames) {
    const glm::vec2 origin(document.router().rectOf(view)->origin);
    std::vector<double> times;
    document.handle(InputEvent::pointerPress(origin + from, PointerButton::Left));
    for (int f = 1; f <= frames; ++f)
        times.push_back(uiFrame(document, [&] { document.handle(InputEvent::pointerMove(origin + from + step * float(f))); }));
    document.handle(InputEvent::pointerRelease(origin + from + step * float(frames), PointerButton::Left));
    return times;
}

} // namespace

int runViewsBench(int argc, char **argv) {
    std::optional<Options> options;
    try {
        options = parseOptions(argc, argv);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench views: %s\n", e.what());
        return 2;
    }
    if (!options) return 0;
    const Options &o = *options;
    try {
        LensRegistry registry;
        for (const Error &e : registry.loadModules(LensRegistry::defaultSearchPath()))
            std::fprintf(stderr, "warning: %s\n", e.what());
        RenderSettings settings;
        settings.width = o.width;
        settings.height = o.height;
        settings.threads = o.threads;
        settings.samplesPerPixel = 1;
        ViewRequest request;
        request.source = o.model;

        const double before = residentMiB();
        Document document(registry, request, settings);
        document.setViewRects({{0, {0, 0}, {o.width, o.height}}});
        renderUntilIdle(document);
        const double oneView = residentMiB();
        document.addView();
        document.setViewRects({{0, {0, 0}, {o.width, o.height}}, {1, {o.width, 0}, {o.width, o.height}}});
        renderUntilIdle(document);
        const double twoViews = residentMiB();
        const TracerBuildStats &build = document.tracer().buildStats();
        std::printf("model   %s, %zu triangles, %d views of %dx%d\n", o.model.c_str(), build.triangles,
                    document.viewCount(), o.width, o.height);
        std::printf("bvh     built once: %.1f MiB, %.0f ms; both views trace it (%s)\n",
                    double(build.memoryBytes) / (1024.0 * 1024.0), build.buildMilliseconds,
                    &document.view(0).tracer() == &document.view(1).tracer() ? "one Tracer" : "TWO TRACERS");
        std::printf("memory  %.1f MiB resident with one view (scene, BVH, view), +%.1f MiB for the second view "
                    "(%.1f MiB per pixel buffer of %dx%d floats)\n",
                    oneView - before, twoViews - oneView,
                    double(o.width) * double(o.height) * 12.0 / (1024.0 * 1024.0), o.width, o.height);

        // A lens drag in view 0 while view 1 has converged and idles.
        Controller &left = document.view(0);
        left.addLens("layer", {0.3f, 0.5f});
        left.setLensProperty(0, "layers", "1-");
        renderUntilIdle(document);
        const std::vector<double> drag =
            dragFrames(document, 0, glm::vec2(0.3f * float(o.width), 0.5f * float(o.height)), {8.f, 0.f}, o.frames);
        std::printf("drag    lens in view 0, view 1 idle: median %.2f ms per UI frame (%d frames of 8 px, input + passes)\n",
                    median(drag), o.frames);

        // Orbit: view 0 alone (view 1 unlinked, idle), then both with linked cameras; runs of
        // each alternate, so that the load of other processes on a shared machine falls on both.
        const glm::vec2 empty(0.05f * float(o.width), 0.05f * float(o.height)); // outside the lens
        std::vector<double> alone, linked;
        double aloneCpu = 0.0, linkedCpu = 0.0;
        for (int run = 0; run < 6; ++run) {
            const bool link = run % 2 == 1;
            if (link) document.link(0, 1, LinkAspect::Camera);
            renderUntilIdle(document);
            const double cpuStart = processCpuSeconds();
            const std::vector<double> frames = dragFrames(document, 0, empty, {(run % 4 < 2 ? 6.f : -6.f), 2.f}, o.frames);
            (link ? linkedCpu : aloneCpu) += processCpuSeconds() - cpuStart;
            (link ? linked : alone).insert((link ? linked : alone).end(), frames.begin(), frames.end());
            if (link) document.unlink(0, 1, LinkAspect::Camera);
        }
        std::printf("orbit   one view %.2f ms, two linked views %.2f ms per UI frame (median): %.2fx wall, %.2fx CPU time\n",
                    median(alone), median(linked), median(linked) / median(alone), linkedCpu / aloneCpu);
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-bench views: %s\n", e.what());
        return 1;
    }
}

} // namespace mvcl::bench
