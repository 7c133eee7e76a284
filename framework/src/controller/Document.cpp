// Document: one scene, several views, one history, links between the views, session files.

#include "Document_p.h"

#include <mvcl/io/LoadedScene.h>
#include <mvcl/io/SceneLoader.h>

#include <algorithm>
#include <chrono>
#include <cctype>

namespace mvcl {

namespace {

constexpr LinkAspect kAspects[] = {LinkAspect::Camera, LinkAspect::Lenses, LinkAspect::Layers};

float aspectOf(const glm::ivec2 &size) { return float(std::max(size.x, 1)) / float(std::max(size.y, 1)); }

/// A file's view camera: its own (or a scene camera it names), else a framing.
Camera fileViewCamera(const ViewSetup &setup, const SessionDescription &file, int view, const Scene &scene,
                      float aspect) {
    ViewSetup viewSetup;
    viewSetup.session = file.view(view);
    ViewRequest plain;
    plain.origin = setup.session.scene;
    return viewSetup.camera(scene, plain, aspect);
}

} // namespace

// --- Private ---------------------------------------------------------------------------------------

std::unique_ptr<Controller> Document::Private::makeView(int index, const Camera &camera, const glm::ivec2 &size) {
    RenderSettings viewSettings = settings;
    viewSettings.width = size.x;
    viewSettings.height = size.y;
    ++linksMuted;
    std::unique_ptr<Controller> view(new Controller(owner, index, camera, viewSettings));
    --linksMuted;
    view->d->contentScale = contentScale;
    if (errorCallback) view->setErrorCallback(errorCallback);
    if (rendering) view->renderSession().start();
    return view;
}

void Document::Private::setView(int index, const Camera &camera, uint32_t visibleLayers, const LensStack &lenses,
                                const std::optional<CompareDescription> &compare) {
    Controller::Private &v = viewOf(index);
    ++linksMuted;
    v.camera = camera;
    v.visibleLayers = visibleLayers;
    v.stack = lenses;
    v.compare.reset();
    if (compare) v.compare = Controller::Private::Compare{compare->lenses, compare->divider, CompareSide::Left};
    v.selected = -1;
    v.sendCamera();
    v.sendBasePolicy();
    v.sendLenses();
    --linksMuted;
}

void Document::Private::fillLayout() {
    while (int(views.size()) < viewGridOf(layout).cellCount()) owner.addView();
    const std::vector<int> shown = owner.shownViews();
    if (std::ranges::find(shown, focus()) == shown.end()) router.setFocus(shown.front());
}

void Document::Private::viewsChanged() {
    if (viewsChangedCallback) viewsChangedCallback();
}

std::vector<int> Document::Private::linkedViews(int from, LinkAspect aspect) const {
    std::vector<int> reached{from};
    for (std::size_t next = 0; next < reached.size(); ++next) // breadth first
        for (const ViewLink &link : links) {
            if (!link.has(aspect) || (link.a != reached[next] && link.b != reached[next])) continue;
            const int other = link.a == reached[next] ? link.b : link.a;
            if (other < int(views.size()) && std::ranges::find(reached, other) == reached.end()) reached.push_back(other);
        }
    return reached;
}

void Document::Private::viewChanged(int from, LinkAspect aspect) {
    if (linksMuted > 0 || links.empty()) return;
    ++linksMuted;
    const std::vector<int> linked = linkedViews(from, aspect);
    for (std::size_t i = 1; i < linked.size(); ++i) copyAspect(from, linked[i], aspect);
    --linksMuted;
}

void Document::Private::copyAspect(int from, int to, LinkAspect aspect) {
    Controller::Private &source = viewOf(from);
    Controller::Private &target = viewOf(to);
    switch (aspect) {
    case LinkAspect::Camera:
        if (target.camera == source.camera) return;
        target.camera = source.camera;
        target.sendCamera();
        return;
    case LinkAspect::Layers:
        if (target.visibleLayers == source.visibleLayers) return;
        target.visibleLayers = source.visibleLayers;
        target.sendBasePolicy();
        return;
    case LinkAspect::Lenses: {
        // Rebuilt from plain values: lens objects are never shared between views, since each
        // is committed in its own view's context.
        Controller::Private::Step step = target.captureStep();
        const std::vector<LensState> wanted = source.captureState().lenses;
        if (step.state.lenses == wanted) return;
        step.state.lenses = wanted;
        try {
            target.restore(step);
        } catch (const Error &e) {
            report(e);
        }
        return;
    }
    }
}

void Document::Private::sharePreviewBudget() {
    for (int i = 0; i < int(views.size()); ++i) {
        const double share = settings.previewBudgetSeconds / double(linkedViews(i, LinkAspect::Camera).size());
        RenderSettings viewSettings = views[std::size_t(i)]->renderSettings();
        if (viewSettings.previewBudgetSeconds == share) continue;
        viewSettings.previewBudgetSeconds = share;
        views[std::size_t(i)]->setRenderSettings(viewSettings);
    }
}

DocumentState Document::Private::state() const {
    DocumentState s;
    for (std::size_t i = 0; i < views.size(); ++i) s.views.push_back(viewOf(int(i)).captureState());
    s.links = links;
    return s;
}

Document::Private::Step Document::Private::captureStep(int view) const {
    Step step{state(), view, {}};
    for (std::size_t i = 0; i < views.size(); ++i) step.selections.push_back(viewOf(int(i)).selected);
    return step;
}

void Document::Private::restore(const Step &step) {
    ++linksMuted;
    try {
        const std::size_t shared = std::min(views.size(), step.state.views.size());
        for (std::size_t i = 0; i < shared; ++i)
            viewOf(int(i)).restore({step.state.views[i], i < step.selections.size() ? step.selections[i] : -1});
    } catch (...) {
        --linksMuted;
        throw;
    }
    --linksMuted;
    links.clear();
    for (const ViewLink &link : step.state.links)
        if (link.b < int(views.size())) links.push_back(link);
    sharePreviewBudget();
    if (step.view < int(views.size())) router.setFocus(step.view);
}

void Document::Private::edit(int view, bool zoom, const std::function<void()> &apply) {
    if (openSteps > 0) {
        apply();
        return;
    }
    const Step before = captureStep(view);
    apply();
    finishStep(before, zoom);
}

void Document::Private::beginEditStep(int view) {
    if (openSteps++ == 0) openStepStart = captureStep(view);
}

void Document::Private::endEditStep() {
    if (openSteps == 0) return;
    if (--openSteps == 0) finishStep(openStepStart, false);
}

void Document::Private::finishStep(const Step &before, bool zoom) {
    if (state() == before.state) return;
    const bool merges = zoom && lastStepWasZoom && !undoSteps.empty() && undoSteps.back().view == before.view;
    if (!merges) {
        undoSteps.push_back(before);
        if (undoSteps.size() > kMaxUndoSteps) undoSteps.erase(undoSteps.begin());
    }
    redoSteps.clear();
    lastStepWasZoom = zoom;
    writeRecovery();
}

void Document::Private::clearHistory() {
    undoSteps.clear();
    redoSteps.clear();
    lastStepWasZoom = false;
}

std::filesystem::path Document::Private::recoveryPath() const {
    if (!explicitRecoveryPath.empty()) return explicitRecoveryPath;
    if (!sessionPath.empty()) return Controller::defaultRecoveryPath(sessionPath);
    return {};
}

void Document::Private::passRecovery(bool changed) {
    recovery.setPath(recoveryPath());
    if (changed) unsaved = true;
    if (const std::optional<Error> error = recovery.pass(changed, [this] { return owner.description(); }))
        report(*error);
}

void Document::Private::markSaved() {
    unsaved = false;
    for (const std::unique_ptr<Controller> &v : views) v->d->stateTouched = false;
    recovery.setPath(recoveryPath());
    recovery.clearPending();
}

void Document::Private::report(const Error &error) const {
    if (!errorCallback) throw error;
    errorCallback(error);
}

// --- construction ---------------------------------------------------------------------------------

Document::Document(const LensRegistry &registry, const ViewRequest &request, const RenderSettings &settings)
    : d(std::make_unique<Private>(*this, registry)) {
    d->settings = settings;
    const glm::ivec2 size(std::max(settings.width, 1), std::max(settings.height, 1));
    ViewSetup setup = ViewSetup::prepare(request, registry);
    LoadedScene loaded = LoadedScene::load(setup.sources(), setup.loadOptions);
    d->scene = std::move(loaded.scene);
    d->tracer = std::move(loaded.tracer);
    const std::optional<SessionDescription> file = std::move(setup.sessionFile);
    const int count = file ? int(file->views.size()) : 1;
    std::vector<Camera> cameras{setup.camera(*d->scene, request, aspectOf(size))};
    for (int i = 1; i < count; ++i) cameras.push_back(fileViewCamera(setup, *file, i, *d->scene, aspectOf(size)));
    const LensStackDescription first = std::move(setup.session);
    setup.session = {};
    setup.sessionFile.reset();
    d->setup = std::move(setup);
    for (int i = 0; i < count; ++i) {
        d->views.push_back(d->makeView(i, cameras[std::size_t(i)], size));
        if (i == 0) {
            const std::optional<CompareDescription> compare = file ? file->views.front().compare : std::nullopt;
            d->setView(0, cameras[0], first.visibleLayers, first.lenses, compare);
        } else {
            const SessionViewDescription &v = file->views[std::size_t(i)];
            d->setView(i, cameras[std::size_t(i)], v.visibleLayers, v.lenses, v.compare);
        }
    }
    // The session's renamed layers, in every view (a view keeps its renames beside the shared scene).
    for (int i = 0; i < count; ++i) d->viewOf(i).setLayerNames(first.layerNames);
    if (file) {
        d->links = file->links;
        d->layout = file->layout;
        d->router.setFocus(file->focus);
        d->fillLayout();
        d->sharePreviewBudget();
    }
    if (!request.sessionFile.empty()) d->sessionPath = request.sessionFile;
    d->markSaved(); // what was opened is not a change to recover; an old copy stays for hasRecovery()
}

Document::~Document() { stopRendering(); }

const LensRegistry &Document::lensRegistry() const { return d->registry; }
const Scene &Document::scene() const { return *d->scene; }
const Tracer &Document::tracer() const { return *d->tracer; }

// --- views ------------------------------------------------------------------------------------------

int Document::viewCount() const { return int(d->views.size()); }

Controller &Document::view(int index) {
    if (index < 0 || index >= viewCount())
        throw Error("document", "no view " + std::to_string(index) + " (there are " + std::to_string(viewCount()) + ")");
    return *d->views[std::size_t(index)];
}

const Controller &Document::view(int index) const { return const_cast<Document *>(this)->view(index); }

int Document::addView() {
    if (viewCount() >= kMaxViews)
        throw Error("document", "a document shows at most " + std::to_string(kMaxViews) + " views");
    const Controller &source = focused();
    const int index = viewCount();
    d->views.push_back(d->makeView(index, source.camera(), source.viewSize()));
    SessionState copy = source.state();
    copy.compare.reset();
    ++d->linksMuted;
    try {
        d->viewOf(index).restore({copy, -1});
    } catch (const Error &e) {
        d->report(e);
    }
    --d->linksMuted;
    d->viewsChanged();
    return index;
}

int Document::focusedView() const { return d->focus(); }

void Document::setFocusedView(int index) {
    view(index); // checks the index
    d->router.setFocus(index);
    updateRenderPriority();
}

// --- layout -----------------------------------------------------------------------------------------

ViewLayout Document::layout() const { return d->layout; }

void Document::setLayout(ViewLayout layout) {
    d->layout = layout;
    d->fillLayout();
    d->writeRecovery();
}

std::vector<int> Document::shownViews() const {
    if (d->layout == ViewLayout::Single) return {focusedView()};
    std::vector<int> shown;
    const int cells = std::min(viewGridOf(d->layout).cellCount(), viewCount());
    for (int i = 0; i < cells; ++i) shown.push_back(i);
    return shown;
}

// --- links ------------------------------------------------------------------------------------------

const std::vector<ViewLink> &Document::links() const { return d->links; }

bool Document::isLinked(int a, int b, LinkAspect aspect) const {
    return std::ranges::any_of(d->links, [&](const ViewLink &link) { return link.joins(a, b) && link.has(aspect); });
}

void Document::link(int a, int b, LinkAspect aspect) {
    view(a);
    view(b);
    if (a == b) throw Error("document", "a view cannot be linked to itself");
    if (isLinked(a, b, aspect)) return;
    const int from = focusedView() == b ? b : a;
    d->edit(from, false, [&] {
        auto existing = std::ranges::find_if(d->links, [&](const ViewLink &link) { return link.joins(a, b); });
        if (existing == d->links.end()) {
            d->links.push_back({std::min(a, b), std::max(a, b)});
            existing = d->links.end() - 1;
        }
        existing->set(aspect, true);
        d->viewChanged(from, aspect);
    });
    d->sharePreviewBudget();
}

void Document::unlink(int a, int b, LinkAspect aspect) {
    if (!isLinked(a, b, aspect)) return;
    d->edit(focusedView(), false, [&] {
        for (ViewLink &link : d->links)
            if (link.joins(a, b)) link.set(aspect, false);
        std::erase_if(d->links, [](const ViewLink &link) { return link.isEmpty(); });
    });
    d->sharePreviewBudget();
}

// --- input ------------------------------------------------------------------------------------------

void Document::setViewRects(const std::vector<ViewRect> &rects, float contentScale) {
    d->contentScale = contentScale;
    d->router.setViewRects(rects);
    for (const ViewRect &rect : rects) view(rect.view).resizeView(rect.size, contentScale);
}

const ViewRouter &Document::router() const { return d->router; }

int Document::dividerDragView() const { return d->dividerView; }

bool Document::handle(const InputEvent &event) {
    if (event.type == InputEvent::Type::Resize) return false;
    if (event.type == InputEvent::Type::FileDrop) {
        // The document's, not a view's: loading a session may replace the views themselves.
        if (event.paths.empty()) return false;
        try {
            const auto session = std::ranges::find_if(event.paths, [](const std::string &path) {
                std::string extension = std::filesystem::path(path).extension().string();
                std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
                return extension == ".json";
            });
            if (session != event.paths.end()) loadSession(*session);
            else openScenes(event.paths);
        } catch (const Error &e) {
            d->report(e);
        }
        return true;
    }
    const int focusBefore = focusedView();
    const ViewRouter::Routed routed = d->router.route(event);
    if (routed.view < 0 || routed.view >= viewCount()) return false;
    Controller &target = view(routed.view);
    const glm::vec2 position = routed.event.position;
    if (d->dividerView == routed.view) { // a divider drag: press to release is one step
        if (event.type == InputEvent::Type::PointerMove) {
            target.setCompareDivider(position.x / float(target.viewSize().x));
            return true;
        }
        if (event.type == InputEvent::Type::PointerRelease && event.button == PointerButton::Left) {
            d->dividerView = -1;
            d->endEditStep();
            return true;
        }
        return false;
    }
    bool changed = false;
    if (event.type == InputEvent::Type::PointerPress && target.isCompareEnabled() && !target.isDragging()) {
        if (event.button == PointerButton::Left && target.isOnCompareDivider(position)) {
            d->dividerView = routed.view;
            d->beginEditStep(routed.view);
            updateRenderPriority();
            return true;
        }
        // A press edits the stack of its side.
        const CompareSide side = target.compareSideAt(position);
        changed = target.compareSide() != side;
        target.setCompareSide(side);
    }
    changed = target.handle(routed.event) || changed;
    if (focusedView() != focusBefore) {
        updateRenderPriority();
        changed = true;
    }
    return changed;
}

// --- files ------------------------------------------------------------------------------------------

SessionDescription Document::description() const {
    SessionDescription session = SessionDescription::fromView(view(0).description());
    session.views.clear();
    for (int i = 0; i < viewCount(); ++i) {
        const Controller &v = view(i);
        SessionViewDescription described;
        const LensStackDescription one = v.description();
        described.camera = one.camera;
        described.visibleLayers = one.visibleLayers;
        described.lenses = one.lenses;
        if (v.isCompareEnabled()) described.compare = CompareDescription{v.compareDivider(), v.rightLensStack()};
        session.views.push_back(std::move(described));
    }
    session.links = d->links;
    session.layout = d->layout;
    session.focus = focusedView();
    return session;
}

void Document::saveSession(const std::filesystem::path &file) {
    writeSessionFile(file, description());
    // Saved: the copy of the unsaved state has nothing left to recover, where it was and where
    // the new session path puts it.
    d->recovery.setPath(d->recoveryPath());
    d->recovery.discard();
    d->sessionPath = file;
    d->markSaved();
    d->recovery.discard();
}

void Document::loadSession(const std::filesystem::path &file) {
    const ViewRequest request = ViewSetup::sessionFileRequest(file, d->setup.loadOptions);
    ViewSetup setup = ViewSetup::prepare(request, d->registry);
    const SessionDescription &sessionFile = *setup.sessionFile;
    const bool keepScene = setup.loadsSameScene(d->setup);
    std::shared_ptr<const Scene> scene = d->scene;
    std::shared_ptr<const Tracer> tracer = d->tracer;
    if (!keepScene) {
        LoadedScene loaded = setup.loadSessionScene(file);
        scene = std::move(loaded.scene);
        tracer = std::move(loaded.tracer);
    }
    const int count = int(sessionFile.views.size());
    std::vector<Camera> cameras;
    for (int i = 0; i < count; ++i) {
        const glm::ivec2 size = view(std::min(i, viewCount() - 1)).viewSize();
        cameras.push_back(i == 0 ? setup.camera(*scene, request, aspectOf(size))
                                 : fileViewCamera(setup, sessionFile, i, *scene, aspectOf(size)));
    }
    // Nothing below throws: the file is read and its scene loaded.
    for (const std::unique_ptr<Controller> &v : d->views)
        if (v->isDragging()) v->d->cancelDrag();
    d->dividerView = -1;
    d->openSteps = 0; // the history starts anew
    const SessionDescription described = sessionFile;
    setup.session = {};
    setup.sessionFile.reset();
    d->setup = std::move(setup);
    d->scene = scene;
    d->tracer = tracer;
    const bool viewsChange = !keepScene || count != viewCount();
    ++d->linksMuted;
    while (viewCount() > count) {
        d->views.back()->renderSession().stop();
        d->views.pop_back();
    }
    for (int i = 0; i < viewCount(); ++i) {
        Controller::Private &v = d->viewOf(i);
        v.setup = d->setup;
        if (!keepScene) v.replaceScene(scene, tracer);
    }
    while (viewCount() < count)
        d->views.push_back(d->makeView(viewCount(), cameras[std::size_t(viewCount())], view(0).viewSize()));
    for (int i = 0; i < count; ++i) {
        const SessionViewDescription &v = described.views[std::size_t(i)];
        d->setView(i, cameras[std::size_t(i)], v.visibleLayers, v.lenses, v.compare);
        d->viewOf(i).setLayerNames(described.common.layerNames);
    }
    --d->linksMuted;
    d->links = described.links;
    d->layout = described.layout;
    d->router.setFocus(described.focus);
    d->fillLayout();
    d->sharePreviewBudget();
    d->sessionPath = file;
    d->clearHistory();
    d->markSaved(); // what was opened is not a change to recover; an old copy stays for hasRecovery()
    if (viewsChange) d->viewsChanged();
}

void Document::openScenes(const std::vector<std::string> &sources, const SceneLoadOptions &options) {
    if (sources.empty()) return;
    if (d->loadJob) {
        d->loadJob->cancel();
        d->cancelledLoads.push_back(std::move(d->loadJob));
    }
    d->loadSetup = ViewSetup{};
    d->loadSetup.source = sources.front();
    d->loadSetup.moreSources.assign(sources.begin() + 1, sources.end());
    d->loadSetup.loadOptions = options;
    d->loadShowedFirst = false;
    // Inference waits for the new scene's first image (updateSceneLoad releases it).
    d->loadJob = std::make_unique<SceneLoadJob>(sources, options, SceneLoadJob::InferenceStart::WhenReleased);
}

bool Document::updateSceneLoad() {
    std::erase_if(d->cancelledLoads, [](const std::unique_ptr<SceneLoadJob> &job) { return job->isFinished(); });
    if (!d->loadJob) return false;
    bool changed = false;
    if (std::optional<SceneLoadJob::Result> result = d->loadJob->takeResult()) {
        // The inferred layers of the scene on screen keep the views as the user left them.
        const bool freshViews = !d->loadShowedFirst;
        if (freshViews) d->setup = d->loadSetup;
        d->installScene(result->scene, result->tracer, freshViews);
        d->loadShowedFirst = true;
        d->loadShownAt = std::chrono::steady_clock::now();
        changed = true;
    }
    // The first image of the scene as read renders on every core; then the layers are inferred
    // (at the latest after a second, so that a view that never finishes a pass cannot hold it).
    if (d->loadShowedFirst && !changed &&
        (focused().renderSession().passCount() > 0 ||
         std::chrono::steady_clock::now() - d->loadShownAt > std::chrono::seconds(1)))
        d->loadJob->releaseInference();
    if (d->loadJob->isFinished() && !changed) {
        const std::optional<Error> error = d->loadJob->error();
        d->loadJob.reset();
        if (error) d->report(*error);
    }
    return changed;
}

bool Document::isLoading() const { return d->loadJob != nullptr; }

std::string Document::loadProgress() const { return d->loadJob ? d->loadJob->progressText() : std::string(); }

void Document::finishSceneLoad() {
    while (d->loadJob) {
        d->loadJob->releaseInference(); // nobody waits for an image here
        d->loadJob->wait();
        updateSceneLoad();
    }
}

void Document::Private::installScene(std::shared_ptr<const Scene> newScene, std::shared_ptr<const Tracer> newTracer,
                                     bool freshViews) {
    ViewRequest request;
    request.source = setup.source;
    request.moreSources = setup.moreSources;
    for (const std::unique_ptr<Controller> &v : views)
        if (v->isDragging()) v->d->cancelDrag();
    scene = std::move(newScene);
    tracer = std::move(newTracer);
    ++linksMuted;
    for (int i = 0; i < owner.viewCount(); ++i) {
        Controller::Private &v = viewOf(i);
        v.setup = setup;
        if (freshViews) {
            v.camera = setup.camera(*scene, request, aspectOf(v.viewSize));
            v.visibleLayers = kAllLayers;
        }
        v.replaceScene(scene, tracer);
    }
    --linksMuted;
    if (!freshViews) return;
    // The links hold on: linked views take the focused view's camera, lenses and layers again.
    for (LinkAspect aspect : kAspects) viewChanged(focus(), aspect);
    clearHistory();
    writeRecovery();
    viewsChanged();
}

const std::filesystem::path &Document::sessionPath() const { return d->sessionPath; }
void Document::setRecoveryPath(const std::filesystem::path &file) { d->explicitRecoveryPath = file; }
std::filesystem::path Document::recoveryPath() const { return d->recoveryPath(); }
void Document::writeRecovery() { d->writeRecovery(); }

// --- history ----------------------------------------------------------------------------------------

void Document::undo() {
    if (d->undoSteps.empty() || d->openSteps > 0) return;
    const Private::Step current = d->captureStep(d->undoSteps.back().view);
    d->restore(d->undoSteps.back());
    d->undoSteps.pop_back();
    d->redoSteps.push_back(current);
    d->lastStepWasZoom = false;
    d->writeRecovery();
}

void Document::redo() {
    if (d->redoSteps.empty() || d->openSteps > 0) return;
    const Private::Step current = d->captureStep(d->redoSteps.back().view);
    d->restore(d->redoSteps.back());
    d->redoSteps.pop_back();
    d->undoSteps.push_back(current);
    d->lastStepWasZoom = false;
    d->writeRecovery();
}

bool Document::canUndo() const { return !d->undoSteps.empty() && d->openSteps == 0; }
bool Document::canRedo() const { return !d->redoSteps.empty() && d->openSteps == 0; }
int Document::undoCount() const { return int(d->undoSteps.size()); }
int Document::redoCount() const { return int(d->redoSteps.size()); }
int Document::undoView() const { return d->undoSteps.empty() ? -1 : d->undoSteps.back().view; }
void Document::beginEditStep() { d->beginEditStep(focusedView()); }
void Document::endEditStep() { d->endEditStep(); }
DocumentState Document::state() const { return d->state(); }

// --- rendering --------------------------------------------------------------------------------------

void Document::startRendering() {
    d->rendering = true;
    for (const std::unique_ptr<Controller> &v : d->views) v->renderSession().start();
    updateRenderPriority();
}

void Document::stopRendering() {
    d->rendering = false;
    for (const std::unique_ptr<Controller> &v : d->views) v->renderSession().stop();
}

void Document::updateRenderPriority() {
    const int focus = focusedView();
    if (focus < 0 || focus >= viewCount()) return;
    const bool focusBusy = view(focus).renderSession().hasWork();
    // While a model is read and its BVH built, the scene it replaces stops refining: the cores
    // go to the load (edits still render).
    const bool reading = d->loadJob && !d->loadShowedFirst;
    for (int i = 0; i < viewCount(); ++i)
        view(i).renderSession().setRefinementHeld(reading || (i != focus && focusBusy));
}

// --- notifications ----------------------------------------------------------------------------------

void Document::setErrorCallback(std::function<void(const Error &)> callback) {
    d->errorCallback = std::move(callback);
    for (const std::unique_ptr<Controller> &v : d->views) v->setErrorCallback(d->errorCallback);
}

void Document::setViewsChangedCallback(std::function<void()> callback) { d->viewsChangedCallback = std::move(callback); }

} // namespace mvcl
