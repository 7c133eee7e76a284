#include <mvcl/view/Renderer.h>

#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include "PixelTracer_p.h"

#include <algorithm>
#include <array>
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
        // In blocks of 4 × 4 pixels, whose primary rays share packets (PixelTracer::addBlockSamples).
        constexpr int kSide = detail::PixelTracer::kBlockSide;
        std::array<uint32_t, kSide * kSide> end;
        end.fill(uint32_t(settings.samplesPerPixel));
        for (int by = y0; by < y1; by += kSide)
            for (int bx = x0; bx < x1; bx += kSide) {
                const int bx1 = std::min(bx + kSide, x1), by1 = std::min(by + kSide, y1);
                std::array<detail::PixelSamples, kSide * kSide> samples{};
                tracer.addBlockSamples(bx, by, bx1, by1, end.data(), samples.data(), size_t(bx1 - bx));
                int i = 0;
                for (int y = by; y < by1; ++y)
                    for (int x = bx; x < bx1; ++x) target.at(x, y) = samples[size_t(i++)].mean();
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
