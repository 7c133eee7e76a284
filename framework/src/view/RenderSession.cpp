#include "RenderSessionPrivate_p.h"

#include <mvcl/core/Error.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

namespace mvcl {

using detail::Clock;
using detail::clipTo;
using detail::sameCamera;
using detail::unite;

namespace {

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
    d->stagedRightStart = -1;
    d->edited();
}

void RenderSession::setLensStacks(const LensStack &left, const LensStack &right, float dividerX) {
    std::lock_guard lock(d->stagedMutex);
    d->stagedLenses = left.lenses();
    d->stagedLenses.insert(d->stagedLenses.end(), right.lenses().begin(), right.lenses().end());
    d->stagedRightStart = left.size();
    d->stagedDivider = std::clamp(dividerX, 0.f, 1.f);
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

RenderPassStats RenderSession::renderUntilIdle() { return renderUntilIdle({}); }

RenderPassStats RenderSession::renderUntilIdle(const std::function<void(const RenderPassStats &)> &afterPass) {
    RenderPassStats total;
    for (;;) {
        const RenderPassStats pass = renderPass();
        if (pass.kind == PassKind::Idle) break;
        if (afterPass) afterPass(pass);
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
            if (!d->gate) {
                d->renderPass();
                continue;
            }
            bool preempted = false;
            {
                std::lock_guard gateLock(d->gate->mutex);
                d->gate->running = &d->seat;
                preempted = d->renderPass().wasCancelled && d->seat.refining.load();
                d->seat.refining = false;
                d->gate->running = nullptr;
            }
            // Let a session waiting at the gate take it before this one takes it again; first of
            // all the one whose edit cancelled this refinement.
            if (preempted) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            else std::this_thread::yield();
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

void RenderSession::setPassGate(std::shared_ptr<RenderPassGate> gate) { d->gate = std::move(gate); }

std::shared_ptr<RenderPassGate> RenderSession::makePassGate() { return std::make_shared<RenderPassGate>(); }

void RenderSession::setRefinementHeld(bool held) {
    std::lock_guard lock(d->stagedMutex);
    d->refinementHeld = held;
    d->wake.notify_all();
}

bool RenderSession::isRefinementHeld() const { return d->refinementHeld.load(); }

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
    c.elapsedSeconds = std::chrono::duration<double>(Clock::now() - d->convergenceResetTime).count();
    return c;
}

std::vector<uint32_t> RenderSession::sampleCounts() const {
    std::vector<uint32_t> counts(d->samples.size());
    for (size_t i = 0; i < counts.size(); ++i) counts[i] = d->samples[i].count;
    return counts;
}

std::vector<float> RenderSession::errorEstimates() const { return {d->errors.begin(), d->errors.end()}; }

std::vector<uint32_t> RenderSession::rayCounts() const {
    std::vector<uint32_t> rays(d->samples.size());
    for (size_t i = 0; i < rays.size(); ++i) rays[i] = d->samples[i].rays;
    return rays;
}

const PolicyMap &RenderSession::policyMap() const { return d->map; }

} // namespace mvcl
