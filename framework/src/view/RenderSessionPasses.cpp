#include "RenderSessionPrivate_p.h"

#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Tracer.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace mvcl {

using detail::Clock;
using detail::clipTo;
using detail::kNoActivePixel;
using detail::unite;
using detail::millisecondsBetween;
using detail::sameCamera;

namespace {

/// Refinement adds at most this many samples per pixel in one pass, so passes stay short
/// enough for the display to update and for a time limit to be met closely.
constexpr uint32_t kMaxSamplesPerPass = 64;
/// Adaptive refinement serves, in one pass, the pixels whose priority is within this factor of
/// the highest: each doubles its samples, which divides its priority by about 4, so the band
/// moves down pass by pass much as a greedy one-sample-at-a-time schedule would.
constexpr float kPriorityBand = 4.f;
/// A preview aims at this share of its budget, so that frames stay under it despite jitter.
constexpr double kPreviewBudgetShare = 0.8;

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

ConvergenceStats RenderSession::Private::summarise() const {
    ConvergenceStats c;
    if (tileSummaries.empty()) return c;
    c.minSamples = std::numeric_limits<int>::max();
    uint64_t countSum = 0, withError = 0, withoutEstimate = 0;
    double errorSum = 0.0, relativeMseSum = 0.0;
    for (const TileSummary &t : tileSummaries) {
        relativeMseSum += t.relativeMseSum;
        withoutEstimate += t.withoutEstimate;
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
    if (withoutEstimate == 0) c.estimatedRelativeMse = relativeMseSum / double(pixelCount());
    c.elapsedSeconds = std::chrono::duration<double>(Clock::now() - resetTime).count();
    c.isConverged = !needsSamples.load();
    if (!c.isConverged && !hasActivePixels()) c.activePixels = 0;
    return c;
}

std::vector<LensCost> RenderSession::Private::lensCosts(const std::vector<PolicyCost> &perPolicy) const {
    LensStack stack;
    // In compare mode the right stack's lenses follow the left's (their lens-set bits too);
    // lenses past the 64th have no bit to be charged by.
    for (const detail::LensState &l : lenses)
        if (stack.size() < LensStack::kMaxLenses) stack.add(l.lens);
    return stack.costs(map, perPolicy);
}

PolicyMap RenderSession::Private::composeStacks(const std::vector<std::shared_ptr<Lens>> &lensList, int splitAt,
                                                int column, const LensContext &context, const RayPolicy &base) const {
    LensStack left, right;
    for (std::size_t i = 0; i < lensList.size(); ++i) (splitAt >= 0 && int(i) >= splitAt ? right : left).add(lensList[i]);
    if (splitAt < 0) return left.compose(context, base, threads());
    return PolicyMap::splice(left.compose(context, base, threads()), right.compose(context, base, threads()), column, splitAt);
}

bool RenderSession::Private::hasWorkLocked() const {
    if (editCount != appliedEdits) return true;
    if (stagedLenses.size() != appliedSnapshots.size()) return true;
    for (size_t i = 0; i < stagedLenses.size(); ++i)
        if (stagedLenses[i]->snapshot().get() != appliedSnapshots[i]) return true;
    if (refinementHeld.load() && onlyRefinementLeft.load()) return passRunning.load();
    return needsSamples.load() || passRunning.load();
}

void RenderSession::Private::resize() {
    const size_t n = pixelCount();
    samples.assign(n, {});
    errors.assign(n, INFINITY);
    priority.assign(n, INFINITY);
    changed.assign(n, 0);
    tilesX = (width() + settings.tileSize - 1) / settings.tileSize;
    tilesY = (height() + settings.tileSize - 1) / settings.tileSize;
    tileFewestUrgent.assign(size_t(tilesX) * size_t(tilesY), 0);
    tileTopPriority.assign(tileFewestUrgent.size(), 0.f);
    tileSummaries.assign(tileFewestUrgent.size(), {});
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

float RenderSession::Private::priorityOf(int x, int y) const {
    const size_t i = size_t(y) * size_t(width()) + size_t(x);
    const uint32_t count = samples[i].count;
    if (count >= samplesWanted()) return 0.f;
    if (settings.sampling != SamplingMode::Adaptive || settings.targetError <= 0.f) return INFINITY;
    if (count < uint32_t(settings.minSamplesPerPixel)) return INFINITY;
    return errorPriority(x, y, samples[i].rays);
}

float RenderSession::Private::errorPriority(int x, int y, uint32_t rays) const {
    // Dilated: a pixel next to one whose estimate is above the target keeps sampling, so that
    // an edge whose pixels happened to agree so far is not left behind.
    float worst = 0.f;
    for (int dy = -1; dy <= 1; ++dy) {
        const int ny = y + dy;
        if (ny < 0 || ny >= height()) continue;
        for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx;
            if (nx < 0 || nx >= width()) continue;
            worst = std::max(worst, errors[size_t(ny) * size_t(width()) + size_t(nx)]);
        }
    }
    if (worst <= settings.targetError) return 0.f;
    // +∞ next to a pixel without an estimate: it waits for it. Every sample costs a ray at least.
    return worst * worst / float(std::max(rays, 1u));
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
    // Every pixel of every traced tile comes here.
    const uint32_t wanted = samplesWanted();
    const bool byError = settings.sampling == SamplingMode::Adaptive && settings.targetError > 0.f;
    const uint32_t minimum = uint32_t(settings.minSamplesPerPixel);
    const auto imageEstimate = byError ? detail::PixelSamples::ImageEstimate::AfterAdaptiveDecisions
                                       : detail::PixelSamples::ImageEstimate::EveryPixelAlike;
    // The sums in locals and the arrays through local pointers, kept in registers: as members
    // of `summary` and of `this` they were stored and reloaded at every pixel.
    uint32_t minCount = kNoActivePixel, maxCount = 0, withError = 0, withoutEstimate = 0;
    uint32_t interiorActive = 0, interiorFewestUrgent = kNoActivePixel;
    uint64_t countSum = 0;
    double errorSum = 0.0, relativeMseSum = 0.0;
    float worstError = 0.f, maxError = 0.f, interiorTopPriority = 0.f;
    const detail::PixelSamples *const sumsOf = samples.data();
    const float *const errorOf = errors.data();
    float *const priorityAt = priority.data();
    const auto summarise = [&](size_t i) {
        const detail::PixelSamples &s = sumsOf[i];
        const uint32_t count = s.count;
        const float error = errorOf[i];
        minCount = std::min(minCount, count);
        maxCount = std::max(maxCount, count);
        countSum += count;
        worstError = std::max(worstError, error);
        if (count >= 2) {
            errorSum += error;
            maxError = std::max(maxError, error);
            ++withError;
            relativeMseSum += s.relativeMse(imageEstimate);
        } else {
            ++withoutEstimate;
        }
    };
    // The tile's interior pixels get their priority here; its border waits for the neighbours.
    const auto prioritise = [&](int x, int y, size_t i) {
        const detail::PixelSamples &s = sumsOf[i];
        const uint32_t count = s.count;
        // priorityOf() with its cheap answers inline.
        const float p = priorityAt[i] = count >= wanted                    ? 0.f
                                        : !byError || count < minimum ? INFINITY
                                                                      : errorPriority(x, y, s.rays);
        if (p > 0.f) ++interiorActive;
        if (p == INFINITY) interiorFewestUrgent = std::min(interiorFewestUrgent, count);
        else interiorTopPriority = std::max(interiorTopPriority, p);
    };
    for (int y = r.y0; y < r.y1; ++y) {
        const size_t row = size_t(y) * size_t(w);
        if (y == r.y0 || y == r.y1 - 1 || r.x1 - r.x0 < 3) {
            for (int x = r.x0; x < r.x1; ++x) summarise(row + size_t(x));
            continue;
        }
        summarise(row + size_t(r.x0));
        for (int x = r.x0 + 1; x < r.x1 - 1; ++x) {
            summarise(row + size_t(x));
            prioritise(x, y, row + size_t(x));
        }
        summarise(row + size_t(r.x1 - 1));
    }
    TileSummary summary;
    summary.minCount = minCount;
    summary.maxCount = maxCount;
    summary.countSum = countSum;
    summary.errorSum = errorSum;
    summary.maxError = maxError;
    summary.worstError = worstError;
    summary.withError = withError;
    summary.relativeMseSum = relativeMseSum;
    summary.withoutEstimate = withoutEstimate;
    summary.interiorActive = interiorActive;
    summary.interiorFewestUrgent = interiorFewestUrgent;
    summary.interiorTopPriority = interiorTopPriority;
    tileSummaries[size_t(tile)] = summary;
}

void RenderSession::Private::finishTile(int tile) {
    const int w = width();
    const PixelRect r = tileRect(tile);
    TileSummary &summary = tileSummaries[size_t(tile)];
    uint32_t fewest = summary.interiorFewestUrgent;
    uint32_t activeCount = summary.interiorActive;
    float top = summary.interiorTopPriority;
    auto visit = [&](int x, int y) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        const float p = priority[i] = priorityOf(x, y);
        if (p > 0.f) ++activeCount;
        if (p == INFINITY) fewest = std::min(fewest, samples[i].count);
        else top = std::max(top, p);
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
    tileFewestUrgent[size_t(tile)] = fewest;
    tileTopPriority[size_t(tile)] = top;
}

void RenderSession::Private::summariseFreshTiles() {
    // resize() left every pixel without samples and with an infinite estimate, so every pixel
    // (and every neighbourhood) is alike: the summaries summariseTile() and finishTile() would
    // make are known from one pixel. Their walk over every pixel was 4 % of a one-sample frame.
    const float p = priorityOf(0, 0);
    if (p != INFINITY) std::fill(priority.begin(), priority.end(), p); // resize() wrote +∞
    for (int tile = 0; tile < int(tileSummaries.size()); ++tile) {
        const PixelRect r = tileRect(tile);
        const uint32_t w = uint32_t(r.x1 - r.x0), h = uint32_t(r.y1 - r.y0);
        const uint32_t pixels = w * h, interior = (w > 2 ? w - 2 : 0) * (h > 2 ? h - 2 : 0);
        TileSummary summary;
        summary.minCount = 0;
        summary.worstError = INFINITY;
        summary.withoutEstimate = pixels;
        summary.interiorFewestUrgent = p == INFINITY && interior > 0 ? 0 : kNoActivePixel;
        summary.interiorActive = p > 0.f ? interior : 0;
        summary.interiorTopPriority = p != INFINITY && interior > 0 ? std::max(0.f, p) : 0.f;
        summary.activeCount = p > 0.f ? pixels : 0;
        tileSummaries[size_t(tile)] = summary;
        tileFewestUrgent[size_t(tile)] = p == INFINITY ? 0 : kNoActivePixel;
        tileTopPriority[size_t(tile)] = p != INFINITY ? std::max(0.f, p) : 0.f;
    }
    stopWhenConverged();
}

void RenderSession::Private::stopWhenConverged() {
    if (settings.sampling == SamplingMode::Progressive && settings.targetError > 0.f) {
        // Progressive stops as a whole once no pixel's estimate is above the target.
        float worst = 0.f;
        for (const TileSummary &t : tileSummaries) worst = std::max(worst, t.worstError);
        if (worst <= settings.targetError) std::fill(tileFewestUrgent.begin(), tileFewestUrgent.end(), kNoActivePixel);
    }
    needsSamples = hasActivePixels() && !timeIsUp();
}

uint32_t RenderSession::Private::fewestUrgent() const {
    return tileFewestUrgent.empty() ? kNoActivePixel
                                    : *std::min_element(tileFewestUrgent.begin(), tileFewestUrgent.end());
}

float RenderSession::Private::topPriority() const {
    return tileTopPriority.empty() ? 0.f : *std::max_element(tileTopPriority.begin(), tileTopPriority.end());
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
    if (!hasActivePixels() || timeIsUp()) {
        needsSamples = false;
        return;
    }
    // Urgent pixels first: the pass brings every urgent pixel below `level` up to it, so pixels
    // restarted by an edit (0 samples) catch up 1, 2, 4, … before the rest go on, and an edit
    // shows within a pass. Then (Adaptive past its minimum) the band of the highest priorities:
    // each of its pixels doubles its samples (at most kMaxSamplesPerPass more).
    const uint32_t wanted = samplesWanted();
    const uint32_t fewest = fewestUrgent();
    const bool urgentPass = fewest != kNoActivePixel;
    const uint32_t level = !urgentPass                          ? 0
                           : settings.sampling == SamplingMode::Fixed ? wanted
                           : std::min(wanted, fewest == 0 ? 1u : fewest + std::min(fewest, kMaxSamplesPerPass));
    const float threshold = urgentPass ? INFINITY : topPriority() / kPriorityBand;
    // By value: captured by reference, every pixel reloaded them (stores to the pixels' sums
    // might alias them, as far as the compiler knows).
    auto samplesToTake = [urgentPass, level, threshold, wanted](float urgency, uint32_t count) -> uint32_t {
        // the pixel's sample count after this pass
        if (urgentPass) return urgency == INFINITY && count < level ? level : count;
        return urgency >= threshold ? std::min(wanted, count + std::min(count, kMaxSamplesPerPass)) : count;
    };
    std::vector<int> work;
    for (int t = 0; t < int(tileFewestUrgent.size()); ++t)
        if (urgentPass ? tileFewestUrgent[size_t(t)] < level : tileTopPriority[size_t(t)] >= threshold) work.push_back(t);
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
        // The per-pixel arrays as local pointers, held in registers: reached through the
        // captured `this`, every pixel reloaded them after each store.
        detail::PixelSamples *const sumsOf = samples.data();
        const float *const urgencyOf = priority.data();
        float *const estimateOf = errors.data();
        glm::vec3 *const shownOf = display.pixels().data(); // display.at(x, y) is shownOf[y · w + x]
        const size_t stride = size_t(w);
        // In blocks of 4 × 4 pixels, whose primary rays share packets (PixelTracer::addBlockSamples).
        constexpr int kSide = detail::PixelTracer::kBlockSide;
        for (int by = r.y0; by < r.y1 && !stopped.load(std::memory_order_relaxed); by += kSide) {
            if (cancel.load(std::memory_order_relaxed) || timeIsUp()) {
                stopped = true;
                break;
            }
            for (int bx = r.x0; bx < r.x1; bx += kSide) {
                const int bx1 = std::min(bx + kSide, r.x1), by1 = std::min(by + kSide, r.y1);
                std::array<uint32_t, kSide * kSide> end;
                uint32_t taking = 0; // bit `count`: the pixel takes samples
                const auto planPixel = [&](int count, size_t i) {
                    const uint32_t has = sumsOf[i].count;
                    const uint32_t after = samplesToTake(urgencyOf[i], has);
                    end[size_t(count)] = after;
                    taking |= uint32_t(after > has) << count;
                };
                int count = 0;
                if (bx1 - bx == kSide && by1 - by == kSide) {
                    // A whole block (most of them): constant bounds.
                    for (int dy = 0; dy < kSide; ++dy)
                        for (int dx = 0; dx < kSide; ++dx)
                            planPixel(dy * kSide + dx, size_t(by + dy) * stride + size_t(bx + dx));
                } else {
                    for (int y = by; y < by1; ++y)
                        for (int x = bx; x < bx1; ++x, ++count) planPixel(count, size_t(y) * stride + size_t(x));
                }
                if (!taking) continue;
                // An edit cancels between blocks: each pixel gets all of its new samples or none.
                if (cancel.load(std::memory_order_relaxed)) {
                    stopped = true;
                    break;
                }
                tracer.addBlockSamples(bx, by, bx1, by1, end.data(), sumsOf + size_t(by) * stride + size_t(bx), stride);
                const auto showPixel = [&](size_t i) {
                    const detail::PixelSamples &sums = sumsOf[i];
                    // relativeError() is +∞ below two samples: asked here, not through a
                    // call per pixel of a one-sample pass.
                    estimateOf[i] = sums.count < 2 ? INFINITY : sums.relativeError();
                    // One sample's mean is its sum (x / 1 is exact): the division was a
                    // third of this loop's time in a one-sample pass.
                    shownOf[i] = sums.count == 1 ? sums.sum : sums.mean();
                };
                if (taking == (1u << (kSide * kSide)) - 1u) {
                    // A whole block, every pixel traced (most blocks of a pass): constant bounds and
                    // no test of `taking` per pixel.
                    for (int dy = 0; dy < kSide; ++dy)
                        for (int dx = 0; dx < kSide; ++dx) showPixel(size_t(by + dy) * stride + size_t(bx + dx));
                    traced += kSide * kSide;
                    continue;
                }
                count = 0;
                for (int y = by; y < by1; ++y)
                    for (int x = bx; x < bx1; ++x, ++count) {
                        if (!((taking >> count) & 1u)) continue;
                        showPixel(size_t(y) * stride + size_t(x));
                        ++traced;
                    }
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
    std::vector<uint8_t> update(tileFewestUrgent.size(), 0);
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
    int newRightStart;
    float newDivider;
    {
        std::lock_guard lock(stagedMutex);
        if (!hasWorkLocked()) return stats;
        newCamera = stagedCamera;
        lensList = stagedLenses;
        newRightStart = stagedRightStart;
        newDivider = stagedDivider;
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
    const int newColumn = newRightStart < 0 ? 0 : int(std::lround(newDivider * float(newSettings.width)));
    const bool dividerMoved = newRightStart >= 0 && newColumn != dividerColumn;
    const bool lensesChanged = !initialised || newBaseVersion != baseVersion || newRightStart != rightStart ||
                               dividerMoved || !detail::sameLenses(newLenses, lenses);
    const bool budgetChanged = initialised && changesBudget(newSettings, settings);
    const RenderSettings oldSettings = settings;
    settings = newSettings;
    camera = newCamera;
    if (restartAll) resize();

    if (lensesChanged || restartAll) {
        const Clock::time_point composeStart = Clock::now();
        PolicyMap newMap = composeStacks(lensList, newRightStart, newColumn, context, base);
        if (!restartAll && !cameraMoved) {
            PixelRect area = newBaseVersion != baseVersion || newRightStart != rightStart
                                 ? PixelRect{0, 0, width(), height()}
                                 : detail::changedArea(lenses, newLenses, width(), height());
            // The strip the divider passed changes stack; markChangedPixels keeps only those of
            // its pixels whose policies differ between the two.
            if (dividerMoved)
                area = unite(area, {std::min(newColumn, dividerColumn), 0, std::max(newColumn, dividerColumn), height()});
            area = clipTo(area, width(), height());
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
        rightStart = newRightStart;
        dividerColumn = newColumn;
        baseVersion = newBaseVersion;
        stats.composeMilliseconds = millisecondsBetween(composeStart, Clock::now());
    }
    if (restartAll || cameraMoved) {
        // resize() has just reset every pixel's samples and estimate: only the tiles' summaries
        // are left to make.
        if (restartAll)
            summariseFreshTiles();
        else
            restartPixels({0, 0, width(), height()}, nullptr);
        stats.pixelsRestarted = pixelCount();
        resetTime = Clock::now();
        fullPassPending = true;
    } else if (budgetChanged) {
        if (oldSettings.timeLimitSeconds != settings.timeLimitSeconds) resetTime = Clock::now();
        updateActive({0, 0, width(), height()});
    }
    initialised = true;
    // A pass that only adds samples: another session's edit may cancel it (RenderPassGate).
    seat.refining = !restartAll && !cameraMoved && !lensesChanged && !budgetChanged && !fullPassPending;

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
        convergenceResetTime = resetTime;
        ++passes;
    }
    onlyRefinementLeft = !fullPassPending;
    passRunning = false;
    return stats;
}

} // namespace mvcl
