#include <mvcl/view/Renderer.h>

#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include "PixelTracer_p.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>

namespace mvcl {

Renderer::Renderer(const Tracer &tracer) : m_tracer(tracer) {}

void Renderer::checkSettings(const RenderSettings &settings, const PolicyMap &policies) {
    if (settings.width < 1 || settings.height < 1 || settings.samplesPerPixel < 1 ||
        settings.tileSize < 1)
        throw Error("render settings", "width, height, samples per pixel and tile size must be ≥ 1");
    if (policies.width() != settings.width || policies.height() != settings.height)
        throw Error("render settings", "policy map size differs from the image size");
}

RenderStats Renderer::render(const Camera &camera, const PolicyMap &policies,
                             const RenderSettings &settings, Framebuffer &target,
                             const ProgressCallback &progress) const {
    checkSettings(settings, policies);
    const int width = settings.width;
    const int height = settings.height;
    if (target.width() != width || target.height() != height) target = Framebuffer(width, height);

    const int tilesX = (width + settings.tileSize - 1) / settings.tileSize;
    const int tilesY = (height + settings.tileSize - 1) / settings.tileSize;
    const int tileCount = tilesX * tilesY;
    const int threads = std::min({settings.threads > 0 ? settings.threads : workerThreadCount(), workerThreadCount(), tileCount});

    const WhittedIntegrator integrator(m_tracer);
    std::atomic<int> tilesDone{0};
    std::mutex statsMutex;
    RenderStats stats;
    stats.perPolicy.resize(policies.policies().size());

    const auto start = std::chrono::steady_clock::now();
    // One task per tile; each tile writes only its own pixels.
    parallelFor(size_t(tileCount), threads, [&](size_t tile) {
        detail::PixelTracer tracer(integrator, camera, policies, settings.seed, stageSelectionOf(settings));
        const int x0 = int(tile % size_t(tilesX)) * settings.tileSize;
        const int y0 = int(tile / size_t(tilesX)) * settings.tileSize;
        const int x1 = std::min(x0 + settings.tileSize, width);
        const int y1 = std::min(y0 + settings.tileSize, height);
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                detail::PixelSamples samples;
                tracer.addSamples(x, y, uint32_t(settings.samplesPerPixel), samples);
                target.at(x, y) = samples.mean();
            }
        }
        tracer.endRun();
        const int done = ++tilesDone;
        std::lock_guard lock(statsMutex);
        stats.rays += tracer.rays();
        tracer.addCostsTo(stats.perPolicy);
        if (progress) progress(float(done) / float(tileCount));
    });
    const auto end = std::chrono::steady_clock::now();

    stats.renderMilliseconds = std::chrono::duration<double, std::milli>(end - start).count();
    stats.threads = threads;
    stats.pixels = uint64_t(width) * uint64_t(height);
    stats.samples = stats.pixels * uint64_t(settings.samplesPerPixel);
    return stats;
}

} // namespace mvcl
