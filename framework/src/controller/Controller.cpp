// Controller: construction, scene and session files, view size, camera, layers, history.
// Lens edits are in ControllerLenses.cpp, input in ControllerInput.cpp.

#include "Controller_p.h"
#include "Document_p.h"

#include <mvcl/io/LoadedScene.h>
#include <mvcl/io/SceneLoader.h>

#include <algorithm>
#include <system_error>

namespace mvcl {


// --- Private helpers ---------------------------------------------------------------------------

RayPolicy Controller::Private::basePolicy() const {
    RayPolicy policy;
    policy.query(RayType::Primary).layerMask = visibleLayers;
    return policy;
}

namespace {

std::vector<LensState> statesOf(const LensStack &stack) {
    std::vector<LensState> states;
    for (const std::shared_ptr<Lens> &lens : stack.lenses()) states.push_back(LensState::of(*lens));
    return states;
}

} // namespace

SessionState Controller::Private::captureState() const {
    SessionState state;
    state.camera = camera;
    state.visibleLayers = visibleLayers;
    state.lenses = statesOf(leftStack());
    if (compare) state.compare = CompareState{statesOf(rightStack()), compare->divider};
    state.layerNames = layerNames;
    return state;
}

LensStack Controller::Private::rebuiltStack(const LensStack &current, const std::vector<LensState> &wanted) const {
    LensStack rebuilt;
    std::vector<bool> reused(std::size_t(current.size()), false);
    const std::vector<LensState> states = statesOf(current);
    for (const LensState &state : wanted) {
        std::shared_ptr<Lens> lens;
        for (std::size_t i = 0; i < states.size() && !lens; ++i)
            if (!reused[i] && states[i] == state) {
                reused[i] = true;
                lens = current.lens(int(i));
            }
        rebuilt.add(lens ? lens : state.create(registry));
    }
    return rebuilt;
}

void Controller::Private::restore(const Step &step) {
    const SessionState &target = step.state;
    // Build the new stacks first, so that a lens that fails to build leaves everything as it
    // was. Lenses already in the wanted state are kept as they are.
    const bool rightEdited = compare && compare->side == CompareSide::Right && target.compare;
    const std::vector<LensState> &editedWanted = rightEdited ? target.compare->lenses : target.lenses;
    LensStack rebuilt = rebuiltStack(stack, editedWanted);
    std::optional<Compare> rebuiltCompare;
    if (target.compare) {
        const std::vector<LensState> &otherWanted = rightEdited ? target.lenses : target.compare->lenses;
        rebuiltCompare = Compare{rebuiltStack(compare ? compare->other : LensStack{}, otherWanted),
                                 target.compare->divider, rightEdited ? CompareSide::Right : CompareSide::Left};
    }
    const bool lensesChanged = rebuilt.lenses() != stack.lenses() || compare.has_value() != rebuiltCompare.has_value() ||
                               (compare && (compare->other.lenses() != rebuiltCompare->other.lenses() ||
                                            compare->divider != rebuiltCompare->divider));
    stack = std::move(rebuilt);
    compare = std::move(rebuiltCompare);
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

void Controller::Private::sendLenses() {
    stateTouched = true;
    placeLenses();
    if (compare) session->setLensStacks(leftStack(), rightStack(), compare->divider);
    else session->setLensStack(stack);
    reportLensFaults();
    tellDocument(LinkAspect::Lenses);
}

void Controller::Private::tellDocument(LinkAspect aspect) {
    if (document) document->viewChanged(viewIndex, aspect);
}

void Controller::Private::editInDocument(StepKind kind, const std::function<void()> &apply) {
    document->edit(viewIndex, kind == StepKind::Zoom, apply);
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
    const bool changed = stateTouched;
    stateTouched = false;
    if (document) return document->passRecovery(changed); // its copy holds every view
    recovery.setPath(q.recoveryPath());
    if (changed) unsaved = true;
    if (const std::optional<Error> error =
            recovery.pass(changed, [this] { return SessionDescription::fromView(q.description()); }))
        report(*error);
}

RecoveryWriter &Controller::Private::recoveryWriter() { return document ? document->recovery : recovery; }

void Controller::Private::markSaved() {
    if (document) return document->markSaved();
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

void Controller::Private::replaceScene(std::shared_ptr<const Scene> newScene, std::shared_ptr<const Tracer> newTracer) {
    const bool wasRunning = session && session->isRunning();
    auto newSession = std::make_unique<RenderSession>(*newTracer);
    newSession->setSettings(sessionSettings());
    if (document) newSession->setPassGate(document->passGate); // the views take turns on the cores
    if (session) session->stop();
    // The old session renders with the old tracer, which points into the old scene.
    session = std::move(newSession);
    tracer = std::move(newTracer);
    scene = std::move(newScene);
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
    LoadedScene loaded = LoadedScene::load(setup.sources(), setup.loadOptions);
    std::shared_ptr<const Scene> scene = std::move(loaded.scene);
    std::shared_ptr<const Tracer> tracer = std::move(loaded.tracer);
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

Controller::Controller(Document &document, int index, const Camera &camera, const RenderSettings &settings)
    : d(std::make_unique<Private>(*this, document.lensRegistry())) {
    Document::Private &owner = *document.d;
    d->document = &owner;
    d->viewIndex = index;
    d->settings = settings;
    d->viewSize = {std::max(settings.width, 1), std::max(settings.height, 1)};
    d->setup = owner.setup;
    d->camera = camera;
    d->replaceScene(owner.scene, owner.tracer);
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
    if (d->document) {
        d->document->openScenes(sources, options);
        return;
    }
    if (d->drag.kind != DragKind::None) d->cancelDrag();
    ViewSetup setup;
    setup.source = sources.front();
    setup.moreSources.assign(sources.begin() + 1, sources.end());
    setup.loadOptions = options;
    ViewRequest request;
    request.source = setup.source;
    request.moreSources = setup.moreSources;
    LoadedScene loaded = LoadedScene::load(sources, options);
    std::shared_ptr<const Scene> scene = std::move(loaded.scene);
    std::shared_ptr<const Tracer> tracer = std::move(loaded.tracer);
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
    LensStackDescription description = d->setup.describe(*d->scene, d->camera, d->leftStack(), d->visibleLayers);
    description.layerNames = d->layerNames;
    return description;
}

void Controller::saveSession(const std::filesystem::path &file) {
    if (d->document) {
        d->document->saveSession(file);
        return;
    }
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
    if (d->document) {
        d->document->loadSession(file);
        return;
    }
    const ViewRequest request = ViewSetup::sessionFileRequest(file, d->setup.loadOptions);
    ViewSetup setup = ViewSetup::prepare(request, d->registry);
    const bool sameScene = setup.loadsSameScene(d->setup);
    std::shared_ptr<const Scene> scene;
    std::shared_ptr<const Tracer> tracer;
    if (!sameScene) {
        LoadedScene loaded = setup.loadSessionScene(file);
        scene = std::move(loaded.scene);
        tracer = std::move(loaded.tracer);
    }
    const Camera camera = setup.camera(sameScene ? *d->scene : *scene, request, coordinates().aspect());
    // Nothing below throws: the file is read and its scene loaded.
    if (d->drag.kind != DragKind::None) d->cancelDrag();
    d->camera = camera;
    d->visibleLayers = setup.session.visibleLayers;
    d->stack = setup.session.lenses;
    d->compare.reset();
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

const std::filesystem::path &Controller::sessionPath() const {
    return d->document ? d->document->sessionPath : d->sessionPath;
}

void Controller::setRecoveryPath(const std::filesystem::path &file) {
    if (d->document) d->document->explicitRecoveryPath = file;
    else d->explicitRecoveryPath = file;
}

std::filesystem::path Controller::recoveryPath() const {
    if (d->document) return d->document->recoveryPath();
    if (!d->explicitRecoveryPath.empty()) return d->explicitRecoveryPath;
    if (!d->sessionPath.empty()) return defaultRecoveryPath(d->sessionPath);
    return {};
}

void Controller::setRecoveryInterval(std::chrono::milliseconds interval) { d->recoveryWriter().setInterval(interval); }
std::chrono::milliseconds Controller::recoveryInterval() const { return d->recoveryWriter().interval(); }
void Controller::updateRecovery() { d->passRecovery(); }
bool Controller::hasUnsavedChanges() const {
    if (!d->document) return d->unsaved || d->stateTouched;
    if (d->document->unsaved) return true;
    for (const std::unique_ptr<Controller> &view : d->document->views)
        if (view->d->stateTouched) return true;
    return false;
}

void Controller::finishRecovery() {
    d->passRecovery();
    if (!hasUnsavedChanges()) {
        d->recoveryWriter().discard();
        return;
    }
    try {
        if (d->document) d->document->recovery.flush([this] { return d->document->owner.description(); });
        else d->recovery.flush([this] { return SessionDescription::fromView(description()); });
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
    const fs::path &session = sessionPath();
    if (session.empty() || !fs::is_regular_file(session, ec)) return true; // never saved
    const fs::file_time_type saved = fs::last_write_time(session, ec);
    return ec || recovered > saved;
}

void Controller::restoreRecovery() {
    const std::filesystem::path recovery = recoveryPath();
    const std::filesystem::path session = sessionPath();
    std::filesystem::path &explicitPath = d->document ? d->document->explicitRecoveryPath : d->explicitRecoveryPath;
    const std::filesystem::path explicitBefore = explicitPath;
    loadSession(recovery);
    // The session is still the one the user opened; the restored state is not saved in it yet,
    // and the copy holds it until it is.
    (d->document ? d->document->sessionPath : d->sessionPath) = session;
    explicitPath = explicitBefore;
    d->recoveryWriter().setPath(recoveryPath());
    (d->document ? d->document->unsaved : d->unsaved) = true;
}

void Controller::discardRecovery() {
    d->recoveryWriter().setPath(recoveryPath());
    d->recoveryWriter().discard();
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
    const auto place = [&context](const LensStack &lenses) {
        for (const std::shared_ptr<Lens> &lens : lenses.lenses()) {
            lens->setContext(context);
            if (!lens->hasUncommittedChanges()) continue;
            try {
                lens->commit();
            } catch (const Error &) { // the render session shows it as it is in this context
            }
        }
    };
    place(stack);
    if (compare) place(compare->other);
}

glm::vec3 Controller::pointUnder(const glm::vec2 &pixel) const {
    Ray ray;
    if (const std::optional<Hit> hit = d->hitUnder(pixel, &ray)) return ray.at(hit->t);
    // Nothing there: the point at the target's depth, where orbiting and panning work too.
    const glm::vec3 forward = -d->camera.sceneFromCamera()[2];
    const float depth = glm::dot(d->camera.target() - d->camera.eye(), forward);
    const float cosine = glm::dot(ray.direction, forward);
    return cosine > 0.f ? ray.at(depth / cosine) : d->camera.target();
}

std::optional<Hit> Controller::Private::hitUnder(const glm::vec2 &pixel, Ray *shot) const {
    const ViewCoordinates view = coordinates();
    // What the pixel shows: the lenses over it (of its side of a compare divider) shape its ray
    // and limit what it may hit.
    const LensStack &shown = q.compareSideAt(pixel) == CompareSide::Left ? leftStack() : rightStack();
    uint64_t lensSet = 0;
    for (int i = 0; i < shown.size(); ++i) {
        const std::shared_ptr<const LensSnapshot> snapshot = shown.lens(i)->snapshot();
        if (snapshot->enabled && snapshot->region.coverage(pixel, view.viewSize().x, view.viewSize().y) >= 0.5f)
            lensSet |= uint64_t(1) << unsigned(i);
    }
    PixelPolicy policy;
    policy.ray = basePolicy();
    try {
        if (lensSet) policy = shown.composeSet(basePolicy(), lensSet);
    } catch (const Error &) { // too many clip volumes: the image shows this as an error too
    }
    const Ray ray = view.rayThroughPixel(camera, policy.samplePosition(pixel, view.viewSize().x, view.viewSize().y));
    if (shot) *shot = ray;
    Hit hit;
    if (tracer->closestHit(ray, policy.ray.query(RayType::Primary), hit)) return hit;
    return std::nullopt;
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
    if (d->document) {
        d->document->owner.undo();
        return;
    }
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
    if (d->document) {
        d->document->owner.redo();
        return;
    }
    if (d->redoSteps.empty() || d->openSteps > 0) return;
    const Private::Step current = d->captureStep();
    d->restore(d->redoSteps.back());
    d->redoSteps.pop_back();
    d->undoSteps.push_back(current);
    d->lastStep = Private::StepKind::Other;
    d->stateTouched = true;
    d->passRecovery();
}

bool Controller::canUndo() const {
    if (d->document) return d->document->owner.canUndo();
    return !d->undoSteps.empty() && d->openSteps == 0;
}
bool Controller::canRedo() const {
    if (d->document) return d->document->owner.canRedo();
    return !d->redoSteps.empty() && d->openSteps == 0;
}
int Controller::undoCount() const { return d->document ? d->document->owner.undoCount() : int(d->undoSteps.size()); }
int Controller::redoCount() const { return d->document ? d->document->owner.redoCount() : int(d->redoSteps.size()); }

void Controller::beginEditStep() {
    if (d->document) {
        d->document->beginEditStep(d->viewIndex);
        return;
    }
    if (d->openSteps++ == 0) d->openStepStart = d->captureStep();
}

void Controller::endEditStep() {
    if (d->document) {
        d->document->endEditStep();
        return;
    }
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
