#include <mvcl/view/RenderSession.h>

#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/lens/PolicyMap.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include "PixelTracer_p.h"
#include "SessionPolicyDiff_p.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <thread>

namespace mvcl {

namespace {

using Clock = std::chrono::steady_clock;
constexpr uint32_t kNoActivePixel = std::numeric_limits<uint32_t>::max();
/// Refinement adds at most this many samples per pixel in one pass, so passes stay short
/// enough for the display to update and for a time limit to be met closely.
constexpr uint32_t kMaxSamplesPerPass = 64;
/// A preview aims at this share of its budget, so that frames stay under it despite jitter.
constexpr double kPreviewBudgetShare = 0.8;

double millisecondsBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

PixelRect unite(const PixelRect &a, const PixelRect &b) {
    if (a.isEmpty()) return b;
    if (b.isEmpty()) return a;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

PixelRect clipTo(const PixelRect &r, int width, int height) {
    return {std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, width), std::min(r.y1, height)};
}

bool sameCamera(const Camera &a, const Camera &b) {
    return a.eye() == b.eye() && a.target() == b.target() && a.up() == b.up() && a.verticalFovDegrees() == b.verticalFovDegrees();
}

/// Settings whose change invalidates every sample taken.
bool changesSamples(const RenderSettings &a, const RenderSettings &b) {
    return a.width != b.width || a.height != b.height || a.tileSize != b.tileSize || a.seed != b.seed;
}

/// Settings whose change only changes which pixels want more samples.
bool changesBudget(const RenderSettings &a, const RenderSettings &b) {
    return a.sampling != b.sampling || a.samplesPerPixel != b.samplesPerPixel ||
           a.minSamplesPerPixel != b.minSamplesPerPixel || a.maxSamplesPerPixel != b.maxSamplesPerPixel ||
           a.targetError != b.targetError || a.timeLimitSeconds != b.timeLimitSeconds;
}

void validate(const RenderSettings &s) {
    auto fail = [](const std::string &problem) { throw Error("render settings", problem); };
    if (s.width < 1 || s.height < 1) fail("width and height must be ≥ 1");
    if (s.samplesPerPixel < 1) fail("samples per pixel must be ≥ 1");
    if (s.tileSize < 1) fail("tile size must be ≥ 1");
    if (s.threads < 0) fail("threads must be ≥ 0 (0 = all cores)");
    if (s.minSamplesPerPixel < 2) fail("minimum samples per pixel must be ≥ 2 (the error estimate needs two)");
    if (s.maxSamplesPerPixel < 1) fail("maximum samples per pixel must be ≥ 1");
    if (!(s.targetError >= 0.f) || !std::isfinite(s.targetError)) fail("target error must be a finite number ≥ 0");
    if (!(s.timeLimitSeconds >= 0.0) || !std::isfinite(s.timeLimitSeconds)) fail("time limit must be a finite number ≥ 0");
    if (!(s.previewBudgetSeconds >= 0.0) || !std::isfinite(s.previewBudgetSeconds))
        fail("preview budget must be a finite number ≥ 0");
}

} // namespace

const char *passKindName(PassKind kind) {
    switch (kind) {
    case PassKind::Idle: return "idle";
    case PassKind::Preview: return "preview";
    case PassKind::Full: return "full";
    case PassKind::Retrace: return "retrace";
    case PassKind::Refine: return "refine";
    }
    return "?";
}

struct RenderSession::Private {
    explicit Private(const Tracer &t) : tracer(t), sceneContext(LensContext::forScene(t.scene())), integrator(t) {}

    const Tracer &tracer;
    const LensContext sceneContext; ///< the scene part of the lenses' context, computed once
    const WhittedIntegrator integrator;

    // --- Staged edits: any thread, under stagedMutex. ---
    mutable std::mutex stagedMutex;
    std::condition_variable wake;
    Camera stagedCamera;
    std::vector<std::shared_ptr<Lens>> stagedLenses;
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

    // --- The accumulated image: the thread that runs passes only. ---
    bool initialised = false;
    Camera camera;
    RenderSettings settings;
    uint64_t baseVersion = 0;
    std::vector<detail::LensState> lenses;
    PolicyMap map{1, 1};
    std::vector<detail::PixelSamples> samples;
    std::vector<float> errors;
    std::vector<uint8_t> active;   ///< the pixel wants more samples
    std::vector<uint8_t> changed;  ///< scratch: pixels whose policy changed
    int tilesX = 0, tilesY = 0;
    std::vector<uint32_t> tileMinCount; ///< fewest samples of an active pixel, or kNoActivePixel
    /// Per tile, what ConvergenceStats sums: kept up to date wherever active flags are, so the
    /// image's stats are a reduction over tiles, not pixels.
    struct TileSummary {
        uint32_t minCount = 0, maxCount = 0;
        uint64_t countSum = 0;
        double errorSum = 0.0;
        float maxError = 0.f;   ///< of the pixels with an estimate (≥ 2 samples)
        float worstError = 0.f; ///< of all pixels, +∞ if one has no estimate yet
        uint32_t withError = 0, activeCount = 0;
        /// Active pixels off the tile's border: their dilation reads this tile's estimates only.
        uint32_t interiorActive = 0, interiorFewest = 0;
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
        wake.notify_all();
    }
    bool hasWorkLocked() const;
    void resize();
    void restartPixels(const PixelRect &area, const std::vector<uint8_t> *only);
    uint32_t samplesWanted() const;
    bool wantsSamples(int x, int y) const;
    void updateActive(const PixelRect &area);
    void updateActiveTiles(const std::vector<int> &tiles);
    void summariseTile(int tile);
    void finishTile(int tile);
    void stopWhenConverged();
    uint32_t minActiveCount() const;
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
};

ConvergenceStats RenderSession::Private::summarise() const {
    ConvergenceStats c;
    if (tileSummaries.empty()) return c;
    c.minSamples = std::numeric_limits<int>::max();
    uint64_t countSum = 0, withError = 0;
    double errorSum = 0.0;
    for (const TileSummary &t : tileSummaries) {
        c.minSamples = std::min(c.minSamples, int(t.minCount));
        c.maxSamples = std::max(c.maxSamples, int(t.maxCount));
        countSum += t.countSum;
        errorSum += t.errorSum;
        withError += t.withError;
        c.maxError = std::max(c.maxError, double(t.maxError));
        c.activePixels += t.activeCount;
    }
    c.meanSamples = double(countSum) / double(pixelCount());
    c.meanError = withError ? errorSum / double(withError) : 0.0;
    c.elapsedSeconds = std::chrono::duration<double>(Clock::now() - resetTime).count();
    c.isConverged = !needsSamples.load();
    if (!c.isConverged && minActiveCount() == kNoActivePixel) c.activePixels = 0;
    return c;
}

std::vector<LensCost> RenderSession::Private::lensCosts(const std::vector<PolicyCost> &perPolicy) const {
    LensStack stack;
    for (const detail::LensState &l : lenses) stack.add(l.lens);
    return stack.costs(map, perPolicy);
}

bool RenderSession::Private::hasWorkLocked() const {
    if (editCount != appliedEdits) return true;
    if (stagedLenses.size() != appliedSnapshots.size()) return true;
    for (size_t i = 0; i < stagedLenses.size(); ++i)
        if (stagedLenses[i]->snapshot().get() != appliedSnapshots[i]) return true;
    return needsSamples.load() || passRunning.load();
}

void RenderSession::Private::resize() {
    const size_t n = pixelCount();
    samples.assign(n, {});
    errors.assign(n, INFINITY);
    active.assign(n, 1);
    changed.assign(n, 0);
    tilesX = (width() + settings.tileSize - 1) / settings.tileSize;
    tilesY = (height() + settings.tileSize - 1) / settings.tileSize;
    tileMinCount.assign(size_t(tilesX) * size_t(tilesY), 0);
    tileSummaries.assign(tileMinCount.size(), {});
    display = Framebuffer(width(), height());
}

void RenderSession::Private::restartPixels(const PixelRect &area, const std::vector<uint8_t> *only) {
    const int w = width();
    parallelFor(size_t(area.y1 - area.y0), threads(), [&](size_t row) {
        const int y = area.y0 + int(row);
        for (int x = area.x0; x < area.x1; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (only && !(*only)[i]) continue;
            samples[i] = {};
            errors[i] = INFINITY;
        }
    });
    updateActive(area);
}

uint32_t RenderSession::Private::samplesWanted() const {
    return uint32_t(settings.sampling == SamplingMode::Fixed ? settings.samplesPerPixel : settings.maxSamplesPerPixel);
}

bool RenderSession::Private::wantsSamples(int x, int y) const {
    const size_t i = size_t(y) * size_t(width()) + size_t(x);
    const uint32_t count = samples[i].count;
    if (count >= samplesWanted()) return false;
    if (settings.sampling != SamplingMode::Adaptive || settings.targetError <= 0.f) return true;
    if (count < uint32_t(settings.minSamplesPerPixel)) return true;
    // Dilated: a pixel next to one whose estimate is above the target keeps sampling, so that
    // an edge whose pixels happened to agree so far is not left behind.
    for (int dy = -1; dy <= 1; ++dy) {
        const int ny = y + dy;
        if (ny < 0 || ny >= height()) continue;
        for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx;
            if (nx < 0 || nx >= width()) continue;
            if (errors[size_t(ny) * size_t(width()) + size_t(nx)] > settings.targetError) return true;
        }
    }
    return false;
}

void RenderSession::Private::updateActive(const PixelRect &area) {
    if (area.isEmpty()) return;
    // Every tile the area touches, plus one pixel around it: a pixel's wish depends on its
    // neighbours' error estimates (dilation).
    const int ts = settings.tileSize;
    const PixelRect grown = clipTo({area.x0 - 1, area.y0 - 1, area.x1 + 1, area.y1 + 1}, width(), height());
    std::vector<int> tiles;
    for (int ty = grown.y0 / ts; ty <= (grown.y1 - 1) / ts; ++ty)
        for (int tx = grown.x0 / ts; tx <= (grown.x1 - 1) / ts; ++tx) tiles.push_back(ty * tilesX + tx);
    updateActiveTiles(tiles);
}

void RenderSession::Private::updateActiveTiles(const std::vector<int> &tiles) {
    parallelFor(tiles.size(), threads(), [&](size_t k) { summariseTile(tiles[k]); });
    parallelFor(tiles.size(), threads(), [&](size_t k) { finishTile(tiles[k]); });
    stopWhenConverged();
}

void RenderSession::Private::summariseTile(int tile) {
    const int w = width();
    const PixelRect r = tileRect(tile);
    TileSummary summary;
    summary.minCount = kNoActivePixel;
    summary.interiorFewest = kNoActivePixel;
    for (int y = r.y0; y < r.y1; ++y) {
        const bool borderRow = y == r.y0 || y == r.y1 - 1;
        for (int x = r.x0; x < r.x1; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const uint32_t count = samples[i].count;
            summary.minCount = std::min(summary.minCount, count);
            summary.maxCount = std::max(summary.maxCount, count);
            summary.countSum += count;
            summary.worstError = std::max(summary.worstError, errors[i]);
            if (count >= 2) {
                summary.errorSum += errors[i];
                summary.maxError = std::max(summary.maxError, errors[i]);
                ++summary.withError;
            }
            if (borderRow || x == r.x0 || x == r.x1 - 1) continue;
            active[i] = wantsSamples(x, y);
            if (active[i]) {
                summary.interiorFewest = std::min(summary.interiorFewest, count);
                ++summary.interiorActive;
            }
        }
    }
    tileSummaries[size_t(tile)] = summary;
}

void RenderSession::Private::finishTile(int tile) {
    const int w = width();
    const PixelRect r = tileRect(tile);
    TileSummary &summary = tileSummaries[size_t(tile)];
    uint32_t fewest = summary.interiorFewest;
    uint32_t activeCount = summary.interiorActive;
    auto visit = [&](int x, int y) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        active[i] = wantsSamples(x, y);
        if (active[i]) {
            fewest = std::min(fewest, samples[i].count);
            ++activeCount;
        }
    };
    for (int y = r.y0; y < r.y1; ++y) {
        if (y == r.y0 || y == r.y1 - 1) {
            for (int x = r.x0; x < r.x1; ++x) visit(x, y);
        } else {
            visit(r.x0, y);
            if (r.x1 - 1 > r.x0) visit(r.x1 - 1, y);
        }
    }
    summary.activeCount = activeCount;
    tileMinCount[size_t(tile)] = fewest;
}

void RenderSession::Private::stopWhenConverged() {
    if (settings.sampling == SamplingMode::Progressive && settings.targetError > 0.f) {
        // Progressive stops as a whole once no pixel's estimate is above the target.
        float worst = 0.f;
        for (const TileSummary &t : tileSummaries) worst = std::max(worst, t.worstError);
        if (worst <= settings.targetError) std::fill(tileMinCount.begin(), tileMinCount.end(), kNoActivePixel);
    }
    needsSamples = minActiveCount() != kNoActivePixel && !timeIsUp();
}

uint32_t RenderSession::Private::minActiveCount() const {
    return tileMinCount.empty() ? kNoActivePixel : *std::min_element(tileMinCount.begin(), tileMinCount.end());
}

int RenderSession::Private::previewDivider() const {
    if (settings.previewBudgetSeconds <= 0.0 || fullNanosecondsPerSample <= 0.0) return 1;
    const double budget = settings.previewBudgetSeconds * 1e9 * kPreviewBudgetShare;
    const double fullPass = double(pixelCount()) * fullNanosecondsPerSample / double(threads());
    if (fullPass <= budget) return 1;
    const double perSample = previewNanosecondsPerSample > 0.0 ? previewNanosecondsPerSample : fullNanosecondsPerSample;
    const double divider = std::ceil(std::sqrt(double(pixelCount()) * perSample / double(threads()) / budget));
    return int(std::clamp(divider, 2.0, 64.0));
}

void RenderSession::Private::publish(const std::vector<int> &tiles, const PixelRect &rect) {
    if (rect.isEmpty()) return;
    std::lock_guard lock(imageMutex);
    if (published.width() != width() || published.height() != height()) {
        published = display;
        publishedChanged = {0, 0, width(), height()};
        return;
    }
    for (int tile : tiles) {
        const PixelRect r = tileRect(tile);
        for (int y = r.y0; y < r.y1; ++y)
            std::copy(&display.at(r.x0, y), &display.at(r.x0, y) + (r.x1 - r.x0), &published.at(r.x0, y));
    }
    publishedChanged = unite(publishedChanged, rect);
}

void RenderSession::Private::tracePass(RenderPassStats &stats) {
    const uint32_t fewest = minActiveCount();
    if (fewest == kNoActivePixel || timeIsUp()) {
        needsSamples = false;
        return;
    }
    // The pass brings every active pixel below `level` up to it. Pixels restarted by an edit
    // (0 samples) catch up 1, 2, 4, … before the rest go on, so an edit shows within a pass.
    const uint32_t wanted = samplesWanted();
    const uint32_t level = settings.sampling == SamplingMode::Fixed
                               ? wanted
                               : std::min(wanted, fewest == 0 ? 1u : fewest + std::min(fewest, kMaxSamplesPerPass));
    std::vector<int> work;
    for (int t = 0; t < int(tileMinCount.size()); ++t)
        if (tileMinCount[size_t(t)] < level) work.push_back(t);
    if (stats.kind == PassKind::Idle) stats.kind = fullPassPending ? PassKind::Full : PassKind::Refine;

    std::mutex merge;
    std::vector<uint8_t> tileDone(work.size(), 0);
    size_t tilesFinished = 0;
    std::atomic<bool> stopped{false};
    const int w = width();
    const Clock::time_point start = Clock::now();
    parallelFor(work.size(), threads(), [&](size_t k) {
        if (stopped.load(std::memory_order_relaxed) || cancel.load(std::memory_order_relaxed)) {
            stopped = true;
            return;
        }
        detail::PixelTracer tracer(integrator, camera, map, settings.seed, stageSelectionOf(settings));
        const PixelRect r = tileRect(work[k]);
        uint64_t traced = 0;
        for (int y = r.y0; y < r.y1 && !stopped.load(std::memory_order_relaxed); ++y) {
            if (cancel.load(std::memory_order_relaxed) || timeIsUp()) {
                stopped = true;
                break;
            }
            for (int x = r.x0; x < r.x1; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                if (!active[i] || samples[i].count >= level) continue;
                // An edit cancels between pixels: each pixel gets all of its new samples or none.
                if (cancel.load(std::memory_order_relaxed)) {
                    stopped = true;
                    break;
                }
                detail::PixelSamples s = samples[i];
                tracer.addSamples(x, y, level, s);
                samples[i] = s;
                errors[i] = s.relativeError();
                display.at(x, y) = s.mean();
                ++traced;
            }
        }
        tracer.endRun();
        // While the tile is in this worker's cache; its border waits for the neighbours.
        if (traced > 0) summariseTile(work[k]);
        std::lock_guard lock(merge);
        stats.rays += tracer.rays();
        stats.samples += tracer.samplesTaken();
        tracer.addCostsTo(stats.perPolicy);
        stats.pixelsTraced += traced;
        tileDone[k] = traced > 0;
        if (progress) progress(float(++tilesFinished) / float(work.size()));
    });
    stats.traceMilliseconds = millisecondsBetween(start, Clock::now());
    stats.wasCancelled = stopped.load();

    std::vector<int> touchedTiles;
    PixelRect rect;
    for (size_t k = 0; k < work.size(); ++k)
        if (tileDone[k]) {
            touchedTiles.push_back(work[k]);
            rect = unite(rect, tileRect(work[k]));
        }
    // The touched tiles and their neighbours: dilation reaches one pixel across tile borders.
    std::vector<uint8_t> update(tileMinCount.size(), 0);
    for (int tile : touchedTiles) {
        const int tx = tile % tilesX, ty = tile / tilesX;
        for (int y = std::max(ty - 1, 0); y <= std::min(ty + 1, tilesY - 1); ++y)
            for (int x = std::max(tx - 1, 0); x <= std::min(tx + 1, tilesX - 1); ++x) update[size_t(y * tilesX + x)] = 1;
    }
    std::vector<int> updateTiles;
    for (size_t t = 0; t < update.size(); ++t)
        if (update[t]) updateTiles.push_back(int(t));
    parallelFor(updateTiles.size(), threads(), [&](size_t k) { finishTile(updateTiles[k]); });
    stopWhenConverged();
    if (!stats.wasCancelled && fewest == 0 && stats.samples > 0) {
        // Thread-time per sample at full resolution: what sizes the next camera preview.
        const double perSample = stats.traceMilliseconds * 1e6 * double(threads()) / double(stats.samples);
        fullNanosecondsPerSample = fullNanosecondsPerSample > 0.0 ? 0.5 * (fullNanosecondsPerSample + perSample) : perSample;
    }
    if (!stats.wasCancelled) fullPassPending = false;
    stats.updated = rect;
    publish(touchedTiles, rect);
}

void RenderSession::Private::previewPass(int divider, RenderPassStats &stats) {
    stats.kind = PassKind::Preview;
    stats.resolutionDivider = divider;
    const int w = width(), h = height();
    const int blocksX = (w + divider - 1) / divider, blocksY = (h + divider - 1) / divider;
    std::mutex merge;
    std::atomic<bool> stopped{false};
    const Clock::time_point start = Clock::now();
    parallelFor(size_t(blocksY), threads(), [&](size_t by) {
        detail::PixelTracer tracer(integrator, camera, map, settings.seed, stageSelectionOf(settings));
        const int y0 = int(by) * divider, y1 = std::min(y0 + divider, h);
        for (int bx = 0; bx < blocksX; ++bx) {
            if (cancel.load(std::memory_order_relaxed)) {
                stopped = true;
                break;
            }
            const int x0 = bx * divider, x1 = std::min(x0 + divider, w);
            const int px = (x0 + x1) / 2, py = (y0 + y1) / 2;
            const glm::vec3 value = tracer.sampleAt(px, py, {float(px) + 0.5f, float(py) + 0.5f});
            for (int y = y0; y < y1; ++y) std::fill(&display.at(x0, y), &display.at(x0, y) + (x1 - x0), value);
        }
        tracer.endRun();
        std::lock_guard lock(merge);
        stats.rays += tracer.rays();
        stats.samples += tracer.samplesTaken();
        tracer.addCostsTo(stats.perPolicy);
    });
    stats.traceMilliseconds = millisecondsBetween(start, Clock::now());
    stats.wasCancelled = stopped.load();
    stats.pixelsTraced = uint64_t(blocksX) * uint64_t(blocksY);
    if (!stats.wasCancelled && stats.samples > 0) {
        const double perSample = stats.traceMilliseconds * 1e6 * double(threads()) / double(stats.samples);
        previewNanosecondsPerSample =
            previewNanosecondsPerSample > 0.0 ? 0.5 * (previewNanosecondsPerSample + perSample) : perSample;
    }
    stats.updated = {0, 0, w, h};
    std::vector<int> all(size_t(tilesX) * size_t(tilesY));
    for (size_t t = 0; t < all.size(); ++t) all[t] = int(t);
    publish(all, stats.updated);
}

RenderPassStats RenderSession::Private::renderPass() {
    const Clock::time_point passStart = Clock::now();
    RenderPassStats stats;

    // 1. Take the staged edits as one consistent state.
    Camera newCamera;
    std::vector<std::shared_ptr<Lens>> lensList;
    RayPolicy base;
    uint64_t newBaseVersion;
    RenderSettings newSettings;
    {
        std::lock_guard lock(stagedMutex);
        if (!hasWorkLocked()) return stats;
        newCamera = stagedCamera;
        lensList = stagedLenses;
        base = stagedBase;
        newBaseVersion = stagedBaseVersion;
        newSettings = stagedSettings;
        appliedEdits = editCount;
        cancel = false;
        passRunning = true;
    }
    // Every lens as it is in this session's scene and view: a lens that depends on the view
    // gets a new snapshot when the camera or size changes, and so a new policy map below.
    LensContext context = sceneContext;
    context.camera = {"", newCamera.eye(), newCamera.target(), newCamera.up(), newCamera.verticalFovDegrees()};
    context.imageWidth = newSettings.width;
    context.imageHeight = newSettings.height;
    std::vector<detail::LensState> newLenses;
    std::vector<const LensSnapshot *> committed; // what hasWork() compares with
    for (const std::shared_ptr<Lens> &lens : lensList) {
        committed.push_back(lens->snapshot().get());
        newLenses.push_back({lens, lens->snapshotIn(context)});
    }
    {
        std::lock_guard lock(stagedMutex);
        appliedSnapshots = std::move(committed);
    }

    // 2. What the edits invalidate.
    const bool restartAll = !initialised || changesSamples(newSettings, settings);
    const bool cameraMoved = initialised && !sameCamera(newCamera, camera);
    const bool lensesChanged = !initialised || newBaseVersion != baseVersion || !detail::sameLenses(newLenses, lenses);
    const bool budgetChanged = initialised && changesBudget(newSettings, settings);
    const RenderSettings oldSettings = settings;
    settings = newSettings;
    camera = newCamera;
    if (restartAll) resize();

    if (lensesChanged || restartAll) {
        const Clock::time_point composeStart = Clock::now();
        LensStack stack;
        for (const std::shared_ptr<Lens> &lens : lensList) stack.add(lens);
        PolicyMap newMap = stack.compose(context, base, threads());
        if (!restartAll && !cameraMoved) {
            const PixelRect area = clipTo(newBaseVersion != baseVersion
                                              ? PixelRect{0, 0, width(), height()}
                                              : detail::changedArea(lenses, newLenses, width(), height()),
                                          width(), height());
            if (!area.isEmpty()) {
                stats.pixelsRestarted = detail::markChangedPixels(map, newMap, area, changed, threads());
                map = std::move(newMap);
                if (stats.pixelsRestarted > 0) {
                    restartPixels(area, &changed);
                    stats.kind = PassKind::Retrace;
                }
            } else {
                map = std::move(newMap);
            }
        } else {
            map = std::move(newMap);
        }
        lenses = std::move(newLenses);
        baseVersion = newBaseVersion;
        stats.composeMilliseconds = millisecondsBetween(composeStart, Clock::now());
    }
    if (restartAll || cameraMoved) {
        restartPixels({0, 0, width(), height()}, nullptr);
        stats.pixelsRestarted = pixelCount();
        resetTime = Clock::now();
        fullPassPending = true;
    } else if (budgetChanged) {
        if (oldSettings.timeLimitSeconds != settings.timeLimitSeconds) resetTime = Clock::now();
        updateActive({0, 0, width(), height()});
    }
    initialised = true;

    // 3. Preview while the camera moves, else trace.
    const int divider = cameraMoved ? previewDivider() : 1;
    if (divider > 1) {
        previewPass(divider, stats);
        needsSamples = true;
    } else {
        tracePass(stats);
    }
    if (!lenses.empty()) stats.perLens = lensCosts(stats.perPolicy);
    stats.milliseconds = millisecondsBetween(passStart, Clock::now());
    const ConvergenceStats reached = summarise();
    {
        std::lock_guard lock(statsMutex);
        last = stats;
        convergence = reached;
        ++passes;
    }
    passRunning = false;
    return stats;
}

RenderSession::RenderSession(const Tracer &tracer) : d(std::make_unique<Private>(tracer)) {}

RenderSession::~RenderSession() { stop(); }

void RenderSession::setCamera(const Camera &camera) {
    std::lock_guard lock(d->stagedMutex);
    if (sameCamera(camera, d->stagedCamera)) return;
    d->stagedCamera = camera;
    d->edited();
}

void RenderSession::setLensStack(const LensStack &stack) {
    std::lock_guard lock(d->stagedMutex);
    d->stagedLenses = stack.lenses();
    d->edited();
}

void RenderSession::setBasePolicy(const RayPolicy &policy) {
    std::lock_guard lock(d->stagedMutex);
    d->stagedBase = policy;
    ++d->stagedBaseVersion;
    d->edited();
}

void RenderSession::setSettings(const RenderSettings &settings) {
    validate(settings);
    std::lock_guard lock(d->stagedMutex);
    d->stagedSettings = settings;
    d->edited();
}

RenderSettings RenderSession::settings() const {
    std::lock_guard lock(d->stagedMutex);
    return d->stagedSettings;
}

Camera RenderSession::camera() const {
    std::lock_guard lock(d->stagedMutex);
    return d->stagedCamera;
}

void RenderSession::setProgressCallback(std::function<void(float)> callback) { d->progress = std::move(callback); }

RenderPassStats RenderSession::renderPass() { return d->renderPass(); }

RenderPassStats RenderSession::renderUntilIdle() {
    RenderPassStats total;
    for (;;) {
        const RenderPassStats pass = renderPass();
        if (pass.kind == PassKind::Idle) break;
        total.kind = pass.kind;
        total.wasCancelled = total.wasCancelled || pass.wasCancelled;
        total.pixelsRestarted += pass.pixelsRestarted;
        total.pixelsTraced += pass.pixelsTraced;
        total.samples += pass.samples;
        total.rays += pass.rays;
        total.composeMilliseconds += pass.composeMilliseconds;
        total.traceMilliseconds += pass.traceMilliseconds;
        total.milliseconds += pass.milliseconds;
        total.updated = unite(total.updated, pass.updated);
        if (total.perPolicy.size() != pass.perPolicy.size()) total.perPolicy.assign(pass.perPolicy.size(), {});
        for (size_t i = 0; i < pass.perPolicy.size(); ++i) {
            total.perPolicy[i].pixels += pass.perPolicy[i].pixels;
            total.perPolicy[i].rays += pass.perPolicy[i].rays;
            total.perPolicy[i].milliseconds += pass.perPolicy[i].milliseconds;
        }
    }
    return total;
}

bool RenderSession::hasWork() const {
    std::lock_guard lock(d->stagedMutex);
    return d->hasWorkLocked();
}

void RenderSession::start() {
    if (d->thread.joinable()) return;
    d->stopping = false;
    d->thread = std::thread([this] {
        for (;;) {
            {
                std::unique_lock lock(d->stagedMutex);
                d->wake.wait(lock, [this] { return d->stopping.load() || d->hasWorkLocked(); });
                if (d->stopping) return;
            }
            d->renderPass();
        }
    });
}

void RenderSession::stop() {
    if (!d->thread.joinable()) return;
    {
        std::lock_guard lock(d->stagedMutex);
        d->stopping = true;
        d->cancel = true;
        d->wake.notify_all();
    }
    d->thread.join();
}

bool RenderSession::isRunning() const { return d->thread.joinable(); }

RenderPassStats RenderSession::lastPass() const {
    std::lock_guard lock(d->statsMutex);
    return d->last;
}

uint64_t RenderSession::passCount() const {
    std::lock_guard lock(d->statsMutex);
    return d->passes;
}

const Framebuffer &RenderSession::image() const { return d->display; }

bool RenderSession::copyImage(Framebuffer &target, PixelRect &changed) {
    std::unique_lock lock(d->imageMutex, std::try_to_lock);
    if (!lock.owns_lock()) return false;
    const Framebuffer &source = d->published;
    if (target.width() != source.width() || target.height() != source.height()) {
        target = source;
        changed = {0, 0, source.width(), source.height()};
    } else {
        changed = clipTo(d->publishedChanged, source.width(), source.height());
        if (!changed.isEmpty())
            for (int y = changed.y0; y < changed.y1; ++y)
                std::copy(&source.at(changed.x0, y), &source.at(changed.x0, y) + (changed.x1 - changed.x0),
                          &target.at(changed.x0, y));
    }
    d->publishedChanged = {};
    return true;
}

ConvergenceStats RenderSession::convergence() const {
    std::lock_guard lock(d->statsMutex);
    ConvergenceStats c = d->convergence;
    if (c.isConverged) return c; // elapsed stops with the work
    c.elapsedSeconds = std::chrono::duration<double>(Clock::now() - d->resetTime).count();
    return c;
}

std::vector<uint32_t> RenderSession::sampleCounts() const {
    std::vector<uint32_t> counts(d->samples.size());
    for (size_t i = 0; i < counts.size(); ++i) counts[i] = d->samples[i].count;
    return counts;
}

std::vector<float> RenderSession::errorEstimates() const { return d->errors; }

const PolicyMap &RenderSession::policyMap() const { return d->map; }

} // namespace mvcl
