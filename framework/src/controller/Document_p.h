#pragma once
// The state behind Document's d-pointer; the views' Controllers call into it (Controller.cpp)
// for their history, files and links.

#include <mvcl/controller/Document.h>

#include "Controller_p.h"

#include <mvcl/controller/RecoveryWriter.h>
#include <mvcl/controller/ViewSetup.h>
#include <mvcl/io/SceneLoadJob.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mvcl {

struct Document::Private {
    Private(Document &document, const LensRegistry &lensRegistry) : owner(document), registry(lensRegistry) {}

    /// What an undo step restores: every view's state and the links, the view the step was
    /// made in (it gets the focus back), and each view's selection.
    struct Step {
        DocumentState state;
        int view = 0;
        std::vector<int> selections;
    };
    static constexpr std::size_t kMaxUndoSteps = 1000;

    Document &owner;
    const LensRegistry &registry;

    // Declared before the views, so that the views (and their sessions) die first.
    ViewSetup setup; ///< source and load options (its session part is not kept)
    std::shared_ptr<const Scene> scene;
    std::shared_ptr<const Tracer> tracer;
    RenderSettings settings;
    std::vector<std::unique_ptr<Controller>> views;
    /// The views' sessions run their passes one at a time on the worker pool.
    std::shared_ptr<RenderPassGate> passGate = RenderSession::makePassGate();

    std::vector<ViewLink> links;
    ViewLayout layout = ViewLayout::Single;
    ViewRouter router;
    float contentScale = 1.f;
    bool rendering = false;
    int dividerView = -1; ///< the view whose compare divider is being dragged

    std::vector<Step> undoSteps;
    std::vector<Step> redoSteps;
    int openSteps = 0;
    Step openStepStart;
    bool lastStepWasZoom = false;
    /// > 0: changes of the views are not copied along the links (while the links themselves
    /// copy, and while undo or loading set every view).
    int linksMuted = 0;

    /// The open in progress (openScenes) and the setup its scene comes with; earlier jobs
    /// cancelled but still finishing their step, so that dropping them does not block the UI.
    std::unique_ptr<SceneLoadJob> loadJob;
    ViewSetup loadSetup;
    bool loadShowedFirst = false; ///< the job's scene as read is installed; the next is the inferred one
    std::chrono::steady_clock::time_point loadShownAt; ///< when it was installed
    std::vector<std::unique_ptr<SceneLoadJob>> cancelledLoads;

    std::filesystem::path sessionPath;
    std::filesystem::path explicitRecoveryPath;
    std::function<void(const Error &)> errorCallback;
    std::function<void()> viewsChangedCallback;

    Controller::Private &viewOf(int index) const { return *views[std::size_t(index)]->d; }
    int focus() const { return router.focus(); }

    // --- views (Document.cpp) ---
    /// A new Controller on the document's scene; links are muted while it sets itself up.
    std::unique_ptr<Controller> makeView(int index, const Camera &camera, const glm::ivec2 &size);
    /// Sets a view to a camera, visible layers and stacks (as read from a file).
    void setView(int index, const Camera &camera, uint32_t visibleLayers, const LensStack &lenses,
                 const std::optional<CompareDescription> &compare);
    void viewsChanged();
    /// Adds views (copies of the focused one) until the layout's cells are filled, and moves
    /// the focus to a shown view.
    void fillLayout();

    // --- links ---
    /// `from` and the views reached from it through links of `aspect`, breadth first.
    std::vector<int> linkedViews(int from, LinkAspect aspect) const;
    /// Copies `aspect` of view `from` to every view reached through links of that aspect.
    void viewChanged(int from, LinkAspect aspect);
    void copyAspect(int from, int to, LinkAspect aspect);
    /// Views whose cameras are linked move together, so they share one UI frame's preview
    /// budget: each gets the app's budget divided by the views it moves with. Called whenever
    /// the links change.
    void sharePreviewBudget();

    // --- history ---
    DocumentState state() const;
    Step captureStep(int view) const;
    void restore(const Step &step);
    void edit(int view, bool zoom, const std::function<void()> &apply);
    void beginEditStep(int view);
    void endEditStep();
    void finishStep(const Step &before, bool zoom);
    void clearHistory();

    // --- recovery (the copy holds every view; the views' Controllers forward to it) ---
    RecoveryWriter recovery;
    bool unsaved = false;          ///< the session changed since it was loaded or saved
    /// A change of the session (`changed`), or a frame's chance for the trailing write.
    void passRecovery(bool changed);
    /// What was loaded or saved is no change to recover.
    void markSaved();

    // --- files ---
    /// Puts a loaded scene in every view: as a new scene (fresh cameras, every layer visible,
    /// links again, a new history) or, for the inferred layers of the scene shown, in place.
    void installScene(std::shared_ptr<const Scene> scene, std::shared_ptr<const Tracer> tracer, bool freshViews);
    void writeRecovery() { passRecovery(true); }
    std::filesystem::path recoveryPath() const;
    void saveSession(const std::filesystem::path &file) { owner.saveSession(file); }
    void loadSession(const std::filesystem::path &file) { owner.loadSession(file); }
    void openScenes(const std::vector<std::string> &sources, const SceneLoadOptions &options) {
        owner.openScenes(sources, options);
    }
    void report(const Error &error) const;
};

} // namespace mvcl
