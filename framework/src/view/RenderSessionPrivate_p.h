#pragma once
// Private: the state behind RenderSession's d-pointer. RenderSession.cpp holds the public
// face (edits staged from any thread, the background thread, the image and stats handed out);
// RenderSessionPasses.cpp the passes (what edits invalidate, which pixels get samples, tracing,
// publishing).

#include <mvcl/view/RenderSession.h>

#include <mvcl/core/WorkerPool.h>
#include <mvcl/lens/LensContext.h>
#include <mvcl/lens/PolicyMap.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include "core/HugePageAllocator_p.h"
#include "PixelTracer_p.h"
#include "SessionPolicyDiff_p.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace mvcl {

namespace detail {

using Clock = std::chrono::steady_clock;
/// A tile's fewest samples when no pixel of it wants any.
constexpr uint32_t kNoActivePixel = std::numeric_limits<uint32_t>::max();

inline double millisecondsBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

inline PixelRect unite(const PixelRect &a, const PixelRect &b) {
    if (a.isEmpty()) return b;
    if (b.isEmpty()) return a;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

inline PixelRect clipTo(const PixelRect &r, int width, int height) {
    return {std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, width), std::min(r.y1, height)};
}

inline bool sameCamera(const Camera &a, const Camera &b) {
    return a.eye() == b.eye() && a.target() == b.target() && a.up() == b.up() && a.verticalFovDegrees() == b.verticalFovDegrees();
}

} // namespace detail

/// What sessions sharing a gate know of each other: who runs a pass, and whether that pass only
/// refines (then another session's edit cancels it).
struct RenderPassGate {
    struct Seat {
        std::atomic<bool> *cancel = nullptr;
        std::atomic<bool> refining{false};
    };
    std::mutex mutex;
    std::atomic<Seat *> running{nullptr};
};

struct RenderSession::Private {
    using Clock = detail::Clock;

    explicit Private(const Tracer &t) : tracer(t), sceneContext(LensContext::forScene(t.scene())), integrator(t) {}

    const Tracer &tracer;
    const LensContext sceneContext; ///< the scene part of the lenses' context, computed once
    const WhittedIntegrator integrator;

    // --- Staged edits: any thread, under stagedMutex. ---
    mutable std::mutex stagedMutex;
    std::condition_variable wake;
    Camera stagedCamera;
    std::vector<std::shared_ptr<Lens>> stagedLenses; ///< compare mode: the left stack, then the right
    int stagedRightStart = -1; ///< index of the right stack's first lens in stagedLenses; -1: no compare
    float stagedDivider = 0.5f;
    RayPolicy stagedBase;
    uint64_t stagedBaseVersion = 0;
    RenderSettings stagedSettings;
    uint64_t editCount = 0;    ///< bumped by every edit
    uint64_t appliedEdits = ~uint64_t(0); ///< editCount the last pass started from
    /// Snapshots the accumulated samples were composed from (compared with the staged lenses'
    /// current ones to see commits made without an edit call).
    std::vector<const LensSnapshot *> appliedSnapshots;
    std::atomic<bool> cancel{false};
    std::atomic<bool> needsSamples{false};
    /// A pass is between taking the edits and publishing its pixels: hasWork() stays true, so
    /// "no work" means the display shows everything.
    std::atomic<bool> passRunning{false};
    std::atomic<bool> refinementHeld{false};
    std::shared_ptr<RenderPassGate> gate; ///< set before start(); may be null
    RenderPassGate::Seat seat{&cancel};
    /// The image is complete at full resolution: what is left is refinement (set by passes).
    std::atomic<bool> onlyRefinementLeft{false};

    // --- The accumulated image: the thread that runs passes only. ---
    bool initialised = false;
    Camera camera;
    RenderSettings settings;
    uint64_t baseVersion = 0;
    std::vector<detail::LensState> lenses;
    int rightStart = -1; ///< as stagedRightStart, for `lenses`
    int dividerColumn = 0; ///< compare mode: the first pixel column of the right stack
    PolicyMap map{1, 1};
    // The per-pixel buffers, the largest a session touches in its first pass: in huge pages.
    std::vector<detail::PixelSamples, detail::HugePageAllocator<detail::PixelSamples>> samples;
    std::vector<float, detail::HugePageAllocator<float>> errors;
    /// Per pixel, what one more sample is worth: 0, it wants no more; +∞, it wants them whatever
    /// its estimate ("urgent": below the minimum, or not Adaptive); else (Adaptive) its dilated
    /// estimate e squared over the rays r its n samples cost. With e² ≈ σ²/n, one more sample
    /// cuts the pixel's expected squared error σ²/n by about σ²/n² ≈ e²/n and costs r/n rays,
    /// so e²/r is the error removed per ray: serving the highest first spends rays where they cut
    /// the image's error most. Samples end up about proportional to σ/√(r/n), the allocation
    /// that minimises the summed squared error for a budget of rays (the cost in rays, not in
    /// time, keeps the image independent of timing and thread count). A pixel under a mirror
    /// costs several rays a sample, one on the background one.
    std::vector<float, detail::HugePageAllocator<float>> priority;
    std::vector<uint8_t> changed;  ///< scratch: pixels whose policy changed
    int tilesX = 0, tilesY = 0;
    std::vector<uint32_t> tileFewestUrgent; ///< fewest samples of an urgent pixel, or kNoActivePixel
    std::vector<float> tileTopPriority;     ///< highest finite priority in the tile, 0 if none
    /// Per tile, what ConvergenceStats sums: kept up to date wherever active flags are, so the
    /// image's stats are a reduction over tiles, not pixels.
    struct TileSummary {
        uint32_t minCount = 0, maxCount = 0;
        uint64_t countSum = 0;
        double errorSum = 0.0;
        float maxError = 0.f;   ///< of the pixels with an estimate (≥ 2 samples)
        float worstError = 0.f; ///< of all pixels, +∞ if one has no estimate yet
        uint32_t withError = 0, activeCount = 0;
        double relativeMseSum = 0.0;   ///< PixelSamples::relativeMse() of the pixels with ≥ 2 samples
        uint32_t withoutEstimate = 0;  ///< pixels with fewer than 2 samples
        /// Pixels off the tile's border: their dilation reads this tile's estimates only.
        uint32_t interiorActive = 0, interiorFewestUrgent = 0;
        float interiorTopPriority = 0.f;
    };
    std::vector<TileSummary> tileSummaries;
    Framebuffer display;
    bool fullPassPending = true;
    Clock::time_point resetTime = Clock::now();
    double fullNanosecondsPerSample = 0.0;    ///< thread-time per sample of full-resolution passes
    double previewNanosecondsPerSample = 0.0; ///< the same for previews

    // --- What other threads read. ---
    std::mutex imageMutex;
    Framebuffer published;
    PixelRect publishedChanged;
    std::function<void(float)> progress;
    mutable std::mutex statsMutex;
    RenderPassStats last;
    ConvergenceStats convergence;
    /// resetTime as of the last finished pass: convergence() measures the elapsed time from it,
    /// since resetTime itself belongs to the thread that runs the passes.
    Clock::time_point convergenceResetTime = Clock::now();
    uint64_t passes = 0;

    // --- Background thread. ---
    std::thread thread;
    std::atomic<bool> stopping{false};

    int threads() const { return settings.threads > 0 ? settings.threads : workerThreadCount(); }
    int width() const { return settings.width; }
    int height() const { return settings.height; }
    size_t pixelCount() const { return size_t(width()) * size_t(height()); }
    PixelRect tileRect(int tile) const {
        const int ts = settings.tileSize;
        const int x0 = (tile % tilesX) * ts, y0 = (tile / tilesX) * ts;
        return {x0, y0, std::min(x0 + ts, width()), std::min(y0 + ts, height())};
    }

    void edited() {
        ++editCount;
        cancel.store(true, std::memory_order_relaxed);
        // Refinement of another session sharing the gate yields to this edit.
        if (gate)
            if (RenderPassGate::Seat *other = gate->running.load(); other && other != &seat && other->refining.load())
                other->cancel->store(true, std::memory_order_relaxed);
        wake.notify_all();
    }
    bool hasWorkLocked() const;
    void resize();
    void restartPixels(const PixelRect &area, const std::vector<uint8_t> *only);
    uint32_t samplesWanted() const;
    float priorityOf(int x, int y) const;
    /// priorityOf() of a pixel with fewer samples than wanted and at least the adaptive minimum,
    /// whose samples cost `rays`: its neighbourhood's worst error against the target.
    float errorPriority(int x, int y, uint32_t rays) const;
    void updateActive(const PixelRect &area);
    void updateActiveTiles(const std::vector<int> &tiles);
    void summariseTile(int tile);
    void finishTile(int tile);
    /// updateActive() of the whole image right after resize(): every pixel alike, so every
    /// tile's summary follows from one pixel's priority, without reading the pixels.
    void summariseFreshTiles();
    void stopWhenConverged();
    uint32_t fewestUrgent() const;
    float topPriority() const;
    bool hasActivePixels() const { return fewestUrgent() != detail::kNoActivePixel || topPriority() > 0.f; }
    bool timeIsUp() const {
        return settings.sampling != SamplingMode::Fixed && settings.timeLimitSeconds > 0.0 &&
               std::chrono::duration<double>(Clock::now() - resetTime).count() >= settings.timeLimitSeconds;
    }
    int previewDivider() const;
    void tracePass(RenderPassStats &stats);
    void previewPass(int divider, RenderPassStats &stats);
    void publish(const std::vector<int> &tiles, const PixelRect &rect);
    RenderPassStats renderPass();
    ConvergenceStats summarise() const;
    std::vector<LensCost> lensCosts(const std::vector<PolicyCost> &perPolicy) const;
    /// The policy map of the stack, or in compare mode (splitAt ≥ 0: the right stack's first
    /// lens) of the two stacks spliced at pixel column `column`.
    PolicyMap composeStacks(const std::vector<std::shared_ptr<Lens>> &lensList, int splitAt, int column,
                            const LensContext &context, const RayPolicy &base) const;
};

} // namespace mvcl
