#include <mvcl/view/Renderer.h>

#include <mvcl/core/Error.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <span>
#include <thread>
#include <vector>

namespace mvcl {

namespace {

/// 32-bit integer hash (lowbias32); turns (pixel, sample, seed) into jitter without shared state,
/// which is what makes the image independent of thread count and tile order.
uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

float unitFloat(uint32_t bits) { return float(bits >> 8) * (1.f / 16777216.f); }

} // namespace

Renderer::Renderer(const Tracer &tracer) : m_tracer(tracer) {}

RenderStats Renderer::render(const Camera &camera, const PolicyMap &policies,
                             const RenderSettings &settings, Framebuffer &target,
                             const ProgressCallback &progress) const {
    if (settings.width < 1 || settings.height < 1 || settings.samplesPerPixel < 1 ||
        settings.tileSize < 1)
        throw Error("render settings", "width, height, samples per pixel and tile size must be ≥ 1");
    if (policies.width() != settings.width || policies.height() != settings.height)
        throw Error("render settings", "policy map size differs from the image size");

    const int width = settings.width;
    const int height = settings.height;
    if (target.width() != width || target.height() != height) target = Framebuffer(width, height);

    const int strata = int(std::ceil(std::sqrt(double(settings.samplesPerPixel))));
    const int spp = settings.samplesPerPixel;
    const int tilesX = (width + settings.tileSize - 1) / settings.tileSize;
    const int tilesY = (height + settings.tileSize - 1) / settings.tileSize;
    const int tileCount = tilesX * tilesY;
    int threads = settings.threads > 0 ? settings.threads
                                       : int(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, tileCount);

    const WhittedIntegrator integrator(m_tracer);
    std::atomic<int> nextTile{0};
    std::atomic<int> tilesDone{0};
    std::mutex statsMutex;
    RayCounters totalRays;
    const size_t policyCount = policies.policies().size();
    std::vector<PolicyCost> totalCosts(policyCount);

    // The mean radiance of one pixel's samples under one policy.
    auto pixelRadiance = [&](int x, int y, const PixelPolicy &policy, RayCounters &rays) {
        const uint32_t pixelKey = hash32(uint32_t(y) * 0x9e3779b1u ^ uint32_t(x) ^ hash32(settings.seed));
        glm::vec3 sum(0.f);
        for (int s = 0; s < spp; ++s) {
            // Stratum s of a strata×strata grid (samples beyond the grid wrap).
            const int cell = s % (strata * strata);
            const uint32_t h = hash32(pixelKey + uint32_t(s) * 0x68e31da4u);
            const float jx = spp == 1 ? 0.5f : unitFloat(h);
            const float jy = spp == 1 ? 0.5f : unitFloat(hash32(h));
            const glm::vec2 pixel(float(x) + (float(cell % strata) + jx) / float(strata),
                                  float(y) + (float(cell / strata) + jy) / float(strata));
            const glm::vec2 sample = policy.samplePosition(pixel, width, height);
            sum += integrator.radiance(camera.generateRay(sample.x, sample.y, width, height), policy.ray, rays);
        }
        return sum / float(spp);
    };

    auto worker = [&]() {
        using Clock = std::chrono::steady_clock;
        auto nanosecondsBetween = [](Clock::time_point a, Clock::time_point b) {
            return std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count();
        };
        RayCounters rays;
        std::vector<PolicyCost> costs(policyCount);
        std::vector<int64_t> nanoseconds(policyCount, 0);
        for (int tile = nextTile++; tile < tileCount; tile = nextTile++) {
            const int x0 = (tile % tilesX) * settings.tileSize;
            const int y0 = (tile / tilesX) * settings.tileSize;
            const int x1 = std::min(x0 + settings.tileSize, width);
            const int y1 = std::min(y0 + settings.tileSize, height);
            // Time is charged to policies per run of equal policy, so the clock is read only
            // where the policy changes (lens edges), not per pixel.
            int runPolicy = -1;
            Clock::time_point runStart = Clock::now();
            auto endRun = [&](Clock::time_point now) {
                if (runPolicy >= 0) nanoseconds[size_t(runPolicy)] += nanosecondsBetween(runStart, now);
                runStart = now;
            };
            for (int y = y0; y < y1; ++y) {
                for (int x = x0; x < x1; ++x) {
                    const std::span<const PolicyTerm> terms = policies.terms(x, y);
                    if (terms.size() == 1) {
                        const uint16_t index = terms[0].policy;
                        if (int(index) != runPolicy) {
                            endRun(Clock::now());
                            runPolicy = index;
                        }
                        const uint64_t raysBefore = rays.total();
                        target.at(x, y) = pixelRadiance(x, y, policies.policy(index), rays);
                        costs[index].rays += rays.total() - raysBefore;
                        ++costs[index].pixels;
                        continue;
                    }
                    // A feathered edge: every blended policy is rendered and timed on its own.
                    endRun(Clock::now());
                    runPolicy = -1;
                    glm::vec3 blended(0.f);
                    for (const PolicyTerm &term : terms) {
                        const uint64_t raysBefore = rays.total();
                        blended += term.weight * pixelRadiance(x, y, policies.policy(term.policy), rays);
                        const Clock::time_point now = Clock::now();
                        nanoseconds[term.policy] += nanosecondsBetween(runStart, now);
                        runStart = now;
                        costs[term.policy].rays += rays.total() - raysBefore;
                        ++costs[term.policy].pixels;
                    }
                    target.at(x, y) = blended;
                }
            }
            endRun(Clock::now());
            const int done = ++tilesDone;
            if (progress) {
                std::lock_guard lock(statsMutex);
                progress(float(done) / float(tileCount));
            }
        }
        std::lock_guard lock(statsMutex);
        totalRays += rays;
        for (size_t i = 0; i < policyCount; ++i) {
            totalCosts[i].pixels += costs[i].pixels;
            totalCosts[i].rays += costs[i].rays;
            totalCosts[i].milliseconds += double(nanoseconds[i]) * 1e-6;
        }
    };

    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    pool.reserve(std::size_t(threads - 1));
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (std::thread &t : pool) t.join();
    const auto end = std::chrono::steady_clock::now();

    RenderStats stats;
    stats.renderMilliseconds = std::chrono::duration<double, std::milli>(end - start).count();
    stats.threads = threads;
    stats.pixels = uint64_t(width) * uint64_t(height);
    stats.samples = stats.pixels * uint64_t(spp);
    stats.rays = totalRays;
    stats.perPolicy = std::move(totalCosts);
    return stats;
}

} // namespace mvcl
