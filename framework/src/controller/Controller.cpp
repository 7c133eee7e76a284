// Controller: construction, scene and session files, view size, camera, layers, history.
// Lens edits are in ControllerLenses.cpp, input in ControllerInput.cpp.

#include "Controller_p.h"

#include <mvcl/io/SceneLoader.h>

#include <algorithm>
#include <system_error>

namespace mvcl {

namespace {

bool sameRules(const LayerRules &a, const LayerRules &b) {
    return std::ranges::equal(a.rules(), b.rules(), [](const LayerRule &x, const LayerRule &y) {
        return x.pattern == y.pattern && x.layer == y.layer && x.name == y.name;
    });
}

/// The same scene source: equal text, or two names of one model file.
bool sameSource(const std::string &a, const std::string &b) {
    if (a == b) return true;
    if (a.starts_with("builtin:") || b.starts_with("builtin:")) return false;
    std::error_code ec;
    return std::filesystem::equivalent(a, b, ec);
}

bool sameSources(const std::vector<std::string> &a, const std::vector<std::string> &b) {
    return std::ranges::equal(a, b, sameSource);
}

} // namespace

// --- Private helpers ---------------------------------------------------------------------------

RayPolicy Controller::Private::basePolicy() const {
    RayPolicy policy;
    policy.query(RayType::Primary).layerMask = visibleLayers;
    return policy;
}

SessionState Controller::Private::captureState() const {
    SessionState state;
    state.camera = camera;
    state.visibleLayers = visibleLayers;
    state.layerNames = layerNames;
    for (const std::shared_ptr<Lens> &lens : stack.lenses()) state.lenses.push_back(LensState::of(*lens));
    return state;
}

void Controller::Private::restore(const Step &step) {
    const SessionState &target = step.state;
    // Build the new stack first, so that a lens that fails to build leaves everything as it
    // was. Lenses already in the wanted state are kept as they are.
    LensStack rebuilt;
    std::vector<bool> reused(std::size_t(stack.size()), false);
    std::vector<LensState> current;
    for (const std::shared_ptr<Lens> &lens : stack.lenses()) current.push_back(LensState::of(*lens));
    for (const LensState &wanted : target.lenses) {
        std::shared_ptr<Lens> lens;
        for (std::size_t i = 0; i < current.size() && !lens; ++i)
            if (!reused[i] && current[i] == wanted) {
                reused[i] = true;
                lens = stack.lens(int(i));
            }
        rebuilt.add(lens ? lens : wanted.create(registry));
    }
    const bool lensesChanged = rebuilt.lenses() != stack.lenses();
    stack = std::move(rebuilt);
    if (lensesChanged) sendLenses();
    if (!(camera == target.camera)) {
        camera = target.camera;
        sendCamera();
    }
    if (visibleLayers != target.visibleLayers) {
        visibleLayers = target.visibleLayers;
        sendBasePolicy();
    }
    if (layerNames != target.layerNames) setLayerNames(target.layerNames);
    selected = step.selected < stack.size() ? step.selected : -1;
}

RenderSettings Controller::Private::sessionSettings() const {
    RenderSettings s = settings;
    s.width = viewSize.x;
    s.height = viewSize.y;
    return s;
}

void Controller::Private::finishStep(const Step &before, StepKind kind) {
    if (captureState() == before.state) return;
    const bool merges = kind == StepKind::Zoom && lastStep == StepKind::Zoom && !undoSteps.empty();
    if (!merges) {
        undoSteps.push_back(before);
        if (undoSteps.size() > kMaxUndoSteps) undoSteps.erase(undoSteps.begin());
    }
    redoSteps.clear();
    lastStep = kind;
    stateTouched = true; // a label changes no rendering, so no send*() said so
    passRecovery();
}

void Controller::Private::clearHistory() {
    undoSteps.clear();
    redoSteps.clear();
    lastStep = StepKind::Other;
}

void Controller::Private::passRecovery() {
    recovery.setPath(q.recoveryPath());
    const RecoveryWriter::Describe describe = [this] { return q.description(); };
    try {
        if (stateTouched) {
            stateTouched = false;
            unsaved = true;
            recovery.sessionChanged(describe);
        } else {
            recovery.update(describe);
        }
        lastRecoveryError.clear();
    } catch (const Error &e) {
        const Error error(e.source(), "recovery copy not written: " + e.problem());
        if (error.what() == lastRecoveryError) return; // tried again one interval later: said already
        lastRecoveryError = error.what();
        report(error);
    }
}

void Controller::Private::markSaved() {
    stateTouched = false;
    unsaved = false;
    recovery.setPath(q.recoveryPath());
    recovery.clearPending();
}

void Controller::Private::reportLensFaults() {
    if (!errorCallback) return;
    std::map<const Lens *, std::string> current;
    for (int i = 0; i < stack.size(); ++i) {
        const Lens &faulty = *stack.lens(i);
        std::string fault = faulty.fault();
        if (fault.empty()) continue;
        const auto known = reportedFaults.find(&faulty);
        if (known == reportedFaults.end() || known->second != fault) errorCallback(Error(lensName(i), "disabled: " + fault));
        current.emplace(&faulty, std::move(fault));
    }
    reportedFaults = std::move(current);
}

void Controller::Private::report(const Error &error) const {
    if (!errorCallback) throw error;
    errorCallback(error);
}

void Controller::Private::replaceScene(std::unique_ptr<Scene> newScene, std::unique_ptr<Tracer> newTracer) {
    const bool wasRunning = session && session->isRunning();
    auto newSession = std::make_unique<RenderSession>(*newTracer);
    newSession->setSettings(sessionSettings());
    if (session) session->stop();
    // The old session renders with the old tracer, which points into the old scene.
    session = std::move(newSession);
    tracer = std::move(newTracer);
    scene = std::move(newScene);
    sceneLayerNames.clear();
    for (const Layer &layer : scene->layers.layers()) sceneLayerNames[layer.id] = layer.name;
    layerNames.clear();
    sendCamera();
    sendBasePolicy();
    sendLenses();
    if (wasRunning) session->start();
}

// --- construction --------------------------------------------------------------------------------

Controller::Controller(const LensRegistry &registry, const ViewRequest &request, const RenderSettings &settings)
    : d(std::make_unique<Private>(*this, registry)) {
    d->settings = settings;
    d->viewSize = {std::max(settings.width, 1), std::max(settings.height, 1)};
    ViewSetup setup = ViewSetup::prepare(request, registry);
    auto scene = std::make_unique<Scene>(loadScene(setup.sources(), setup.loadOptions));
    auto tracer = std::make_unique<Tracer>(*scene);
    d->camera = setup.camera(*scene, request, float(d->viewSize.x) / float(d->viewSize.y));
    d->visibleLayers = setup.session.visibleLayers;
    d->stack = setup.session.lenses;
    std::map<int, std::string> layerNames = std::move(setup.session.layerNames);
    setup.session = {}; // the controller's stack is the one that is edited
    d->setup = std::move(setup);
    d->replaceScene(std::move(scene), std::move(tracer));
    d->setLayerNames(std::move(layerNames));
    if (!request.sessionFile.empty()) d->sessionPath = request.sessionFile;
    d->markSaved(); // what was opened is not a change to recover; an old copy stays for hasRecovery()
}

Controller::~Controller() {
    if (d->session) d->session->stop();
}

// --- scene ------------------------------------------------------------------------------------------

const Scene &Controller::scene() const { return *d->scene; }
const Tracer &Controller::tracer() const { return *d->tracer; }
RenderSession &Controller::renderSession() { return *d->session; }
const std::string &Controller::sceneSource() const { return d->setup.source; }
std::vector<std::string> Controller::sceneSources() const { return d->setup.sources(); }
const SceneLoadOptions &Controller::sceneLoadOptions() const { return d->setup.loadOptions; }

void Controller::openScene(const std::string &source, const SceneLoadOptions &options) {
    openScenes({source}, options);
}

void Controller::openScenes(const std::vector<std::string> &sources, const SceneLoadOptions &options) {
    if (sources.empty()) return;
    if (d->drag.kind != DragKind::None) d->cancelDrag();
    ViewSetup setup;
    setup.source = sources.front();
    setup.moreSources.assign(sources.begin() + 1, sources.end());
    setup.loadOptions = options;
    ViewRequest request;
    request.source = setup.source;
    request.moreSources = setup.moreSources;
    auto scene = std::make_unique<Scene>(loadScene(sources, options));
    auto tracer = std::make_unique<Tracer>(*scene);
    const Camera camera = setup.camera(*scene, request, coordinates().aspect());
    // Nothing below throws: the new scene is complete.
    d->setup = std::move(setup);
    d->camera = camera;
    d->visibleLayers = kAllLayers;
    d->replaceScene(std::move(scene), std::move(tracer));
    d->clearHistory();
    d->passRecovery(); // another model is a change of the session
    if (d->sceneChangedCallback) d->sceneChangedCallback();
}

// --- session files ----------------------------------------------------------------------------------

LensStackDescription Controller::description() const {
    LensStackDescription description = d->setup.describe(*d->scene, d->camera, d->stack, d->visibleLayers);
    description.layerNames = d->layerNames;
    return description;
}

void Controller::saveSession(const std::filesystem::path &file) {
    writeLensStackFile(file, description());
    // Saved: the copy of the unsaved state has nothing left to recover, where it was and where
    // the new session path puts it.
    d->recovery.setPath(recoveryPath());
    d->recovery.discard();
    d->sessionPath = file;
    d->markSaved();
    d->recovery.discard();
}

void Controller::loadSession(const std::filesystem::path &file) {
    ViewRequest request;
    request.sessionFile = file;
    request.origin = file.string(); // "no scene given" is the file's problem here
    // The app's way of loading (default lights, inference) stays; the rules are the file's.
    request.loadOptions = d->setup.loadOptions;
    request.loadOptions.layerRules = {};
    request.loadOptions.layerContact = {}; // the file's contact tolerance, like its rules
    ViewSetup setup = ViewSetup::prepare(request, d->registry);
    const bool sameScene = sameSources(setup.sources(), d->setup.sources()) &&
                           sameRules(setup.loadOptions.layerRules, d->setup.loadOptions.layerRules) &&
                           setup.loadOptions.layerContact == d->setup.loadOptions.layerContact;
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Tracer> tracer;
    if (!sameScene) {
        try {
            scene = std::make_unique<Scene>(loadScene(setup.sources(), setup.loadOptions));
        } catch (const Error &e) { // the scene's own error, said to be the session file's scene
            throw Error(file.string(), "scene: " + std::string(e.what()));
        }
        tracer = std::make_unique<Tracer>(*scene);
    }
    const Camera camera = setup.camera(sameScene ? *d->scene : *scene, request, coordinates().aspect());
    // Nothing below throws: the file is read and its scene loaded.
    if (d->drag.kind != DragKind::None) d->cancelDrag();
    d->camera = camera;
    d->visibleLayers = setup.session.visibleLayers;
    d->stack = setup.session.lenses;
    d->selected = -1;
    std::map<int, std::string> layerNames = std::move(setup.session.layerNames);
    setup.session = {};
    d->setup = std::move(setup);
    if (sameScene) {
        d->sendCamera();
        d->sendBasePolicy();
        d->sendLenses();
    } else {
        d->replaceScene(std::move(scene), std::move(tracer));
    }
    d->setLayerNames(std::move(layerNames));
    d->sessionPath = file;
    d->clearHistory();
    d->markSaved();
    if (!sameScene && d->sceneChangedCallback) d->sceneChangedCallback();
}

const std::filesystem::path &Controller::sessionPath() const { return d->sessionPath; }

void Controller::setRecoveryPath(const std::filesystem::path &file) { d->explicitRecoveryPath = file; }

std::filesystem::path Controller::recoveryPath() const {
    if (!d->explicitRecoveryPath.empty()) return d->explicitRecoveryPath;
    if (!d->sessionPath.empty()) return defaultRecoveryPath(d->sessionPath);
    return {};
}

void Controller::setRecoveryInterval(std::chrono::milliseconds interval) { d->recovery.setInterval(interval); }
std::chrono::milliseconds Controller::recoveryInterval() const { return d->recovery.interval(); }
void Controller::updateRecovery() { d->passRecovery(); }
bool Controller::hasUnsavedChanges() const { return d->unsaved || d->stateTouched; }

void Controller::finishRecovery() {
    d->passRecovery();
    if (!hasUnsavedChanges()) {
        d->recovery.discard();
        return;
    }
    try {
        d->recovery.flush([this] { return description(); });
    } catch (const Error &e) {
        d->report(Error(e.source(), "recovery copy not written: " + e.problem()));
    }
}

bool Controller::hasRecovery() const {
    namespace fs = std::filesystem;
    const fs::path recovery = recoveryPath();
    std::error_code ec;
    if (recovery.empty() || !fs::is_regular_file(recovery, ec)) return false;
    const fs::file_time_type recovered = fs::last_write_time(recovery, ec);
    if (ec) return false;
    if (d->sessionPath.empty() || !fs::is_regular_file(d->sessionPath, ec)) return true; // never saved
    const fs::file_time_type saved = fs::last_write_time(d->sessionPath, ec);
    return ec || recovered > saved;
}

void Controller::restoreRecovery() {
    const std::filesystem::path recovery = recoveryPath();
    const std::filesystem::path session = d->sessionPath;
    const std::filesystem::path explicitPath = d->explicitRecoveryPath;
    loadSession(recovery);
    // The session is still the one the user opened; the restored state is not saved in it yet,
    // and the copy holds it until it is.
    d->sessionPath = session;
    d->explicitRecoveryPath = explicitPath;
    d->recovery.setPath(recoveryPath());
    d->unsaved = true;
}

void Controller::discardRecovery() {
    d->recovery.setPath(recoveryPath());
    d->recovery.discard();
}

std::filesystem::path Controller::defaultRecoveryPath(const std::filesystem::path &sessionFile) {
    std::filesystem::path recovery = sessionFile;
    recovery.replace_filename(sessionFile.stem().string() + ".recovery.json");
    return recovery;
}

// --- view size and rendering ------------------------------------------------------------------------

glm::ivec2 Controller::viewSize() const { return d->viewSize; }
float Controller::contentScale() const { return d->contentScale; }

void Controller::resizeView(const glm::ivec2 &framebufferSize, float contentScale) {
    const glm::ivec2 size(std::max(framebufferSize.x, 1), std::max(framebufferSize.y, 1));
    d->contentScale = contentScale > 0.f ? contentScale : 1.f;
    if (size == d->viewSize) return;
    d->viewSize = size;
    d->session->setSettings(d->sessionSettings());
}

void Controller::setRenderSettings(const RenderSettings &settings) {
    d->settings = settings;
    d->session->setSettings(d->sessionSettings());
}

RenderSettings Controller::renderSettings() const { return d->sessionSettings(); }
ViewCoordinates Controller::coordinates() const { return d->coordinates(); }

// --- camera -----------------------------------------------------------------------------------------

Camera Controller::camera() const { return d->camera; }

void Controller::setCamera(const Camera &camera) {
    d->edit(Private::StepKind::Other, [&] {
        d->camera = camera;
        d->sendCamera();
    });
}

void Controller::orbit(float yawRadians, float pitchRadians) {
    setCamera(orbitCamera(d->camera, yawRadians, pitchRadians));
}

void Controller::pan(const glm::vec2 &pixelOffset) { setCamera(panCamera(d->camera, pixelOffset, d->viewSize)); }

void Controller::zoomAt(const glm::vec2 &pixel, float factor) {
    const Camera zoomed = zoomCamera(d->camera, factor, pointUnder(pixel));
    d->edit(Private::StepKind::Zoom, [&] {
        d->camera = zoomed;
        d->sendCamera();
    });
}

void Controller::frameAll() { setCamera(framedCamera(d->camera, d->scene->bounds(), coordinates().aspect())); }

void Controller::setViewPreset(ViewPreset preset) {
    setCamera(presetCamera(d->camera, preset, d->scene->bounds(), coordinates().aspect()));
}

void Controller::Private::placeLenses() {
    if (!scene) return;
    if (sceneOfContext != scene.get()) {
        sceneContext = LensContext::forScene(*scene);
        sceneOfContext = scene.get();
    }
    LensContext context = sceneContext;
    context.camera = {"", camera.eye(), camera.target(), camera.up(), camera.verticalFovDegrees()};
    context.imageWidth = viewSize.x;
    context.imageHeight = viewSize.y;
    for (const std::shared_ptr<Lens> &lens : stack.lenses()) {
        lens->setContext(context);
        if (!lens->hasUncommittedChanges()) continue;
        try {
            lens->commit();
        } catch (const Error &) { // the render session shows it as it is in this context
        }
    }
}

glm::vec3 Controller::pointUnder(const glm::vec2 &pixel) const {
    const ViewCoordinates view = coordinates();
    // What the pixel shows: the lenses over it shape its ray and limit what it may hit.
    uint64_t lensSet = 0;
    for (int i = 0; i < d->stack.size(); ++i) {
        const std::shared_ptr<const LensSnapshot> snapshot = d->stack.lens(i)->snapshot();
        if (snapshot->enabled && snapshot->region.coverage(pixel, view.viewSize().x, view.viewSize().y) >= 0.5f)
            lensSet |= uint64_t(1) << unsigned(i);
    }
    PixelPolicy policy;
    policy.ray = d->basePolicy();
    try {
        if (lensSet) policy = d->stack.composeSet(d->basePolicy(), lensSet);
    } catch (const Error &) { // too many clip volumes: the image shows this as an error too
    }
    const Ray ray =
        view.rayThroughPixel(d->camera, policy.samplePosition(pixel, view.viewSize().x, view.viewSize().y));
    Hit hit;
    if (d->tracer->closestHit(ray, policy.ray.query(RayType::Primary), hit)) return ray.at(hit.t);
    // Nothing there: the point at the target's depth, where orbiting and panning work too.
    const glm::vec3 forward = -d->camera.sceneFromCamera()[2];
    const float depth = glm::dot(d->camera.target() - d->camera.eye(), forward);
    const float cosine = glm::dot(ray.direction, forward);
    return cosine > 0.f ? ray.at(depth / cosine) : d->camera.target();
}

// --- layers -----------------------------------------------------------------------------------------

void Controller::setLayerVisibility(int layer, LayerVisibility visibility) {
    if (layer < 0 || layer >= kMaxLayers)
        throw Error("layer visibility", "layer " + std::to_string(layer) + " is outside 0.." +
                                            std::to_string(kMaxLayers - 1));
    const uint32_t bit = uint32_t(1) << unsigned(layer);
    setVisibleLayers(visibility == LayerVisibility::Visible ? d->visibleLayers | bit : d->visibleLayers & ~bit);
}

LayerVisibility Controller::layerVisibility(int layer) const {
    if (layer < 0 || layer >= kMaxLayers) return LayerVisibility::Hidden;
    return (d->visibleLayers >> unsigned(layer)) & 1u ? LayerVisibility::Visible : LayerVisibility::Hidden;
}

uint32_t Controller::visibleLayers() const { return d->visibleLayers; }

void Controller::setVisibleLayers(uint32_t mask) {
    if (mask == d->visibleLayers) return;
    d->edit(Private::StepKind::Other, [&] {
        d->visibleLayers = mask;
        d->sendBasePolicy();
    });
}

RayPolicy Controller::basePolicy() const { return d->basePolicy(); }

// --- history -------------------------------------------------------------------------------------------

void Controller::undo() {
    if (d->undoSteps.empty() || d->openSteps > 0) return;
    const Private::Step current = d->captureStep();
    d->restore(d->undoSteps.back());
    d->undoSteps.pop_back();
    d->redoSteps.push_back(current);
    d->lastStep = Private::StepKind::Other;
    d->stateTouched = true;
    d->passRecovery();
}

void Controller::redo() {
    if (d->redoSteps.empty() || d->openSteps > 0) return;
    const Private::Step current = d->captureStep();
    d->restore(d->redoSteps.back());
    d->redoSteps.pop_back();
    d->undoSteps.push_back(current);
    d->lastStep = Private::StepKind::Other;
    d->stateTouched = true;
    d->passRecovery();
}

bool Controller::canUndo() const { return !d->undoSteps.empty() && d->openSteps == 0; }
bool Controller::canRedo() const { return !d->redoSteps.empty() && d->openSteps == 0; }
int Controller::undoCount() const { return int(d->undoSteps.size()); }
int Controller::redoCount() const { return int(d->redoSteps.size()); }

void Controller::beginEditStep() {
    if (d->openSteps++ == 0) d->openStepStart = d->captureStep();
}

void Controller::endEditStep() {
    if (d->openSteps == 0) return;
    if (--d->openSteps == 0) d->finishStep(d->openStepStart, Private::StepKind::Other);
}

SessionState Controller::state() const { return d->captureState(); }

// --- notifications ----------------------------------------------------------------------------------

void Controller::setErrorCallback(std::function<void(const Error &)> callback) {
    d->errorCallback = std::move(callback);
    d->reportLensFaults(); // lenses of a session read before there was a callback
}

void Controller::setSceneChangedCallback(std::function<void()> callback) {
    d->sceneChangedCallback = std::move(callback);
}

} // namespace mvcl
