#pragma once
/// \file Document.h
/// One scene and several views of it, without a window system. The document owns the scene
/// and its tracer (one BVH, built once) and up to kMaxViews views; each view is a Controller
/// with its own camera, lens stack (or two, in compare mode), visible layers, selection and
/// RenderSession over the shared tracer.
///
/// What is the document's rather than a view's:
/// - one undo history across the views: every edit step remembers the view it was made in,
///   and undo puts the focus back there (Ctrl+Z / Ctrl+Y in any view go here);
/// - links (ViewLink): two-way, per aspect (camera, lenses, layers). After any change of a
///   view's linked aspect the document copies it to every view reached through links of that
///   aspect, during a drag too, inside the same undo step. Lens objects are never shared: a
///   linked view rebuilds its own lenses from their LensState. A link survives saving,
///   reopening and reloading the model. Making or removing one is an undo step; a new link
///   copies the focused view (or its first view) to the other;
/// - the session file (SessionFile.h: views, links, layout, compare divider) and its
///   recovery copy, written after every step through writeRecovery();
/// - opening another model: loaded once, every view's session replaced, the lens stacks and
///   links kept;
/// - input routing (ViewRouter): pointer events go to the view under the pointer (the pressed
///   view keeps them until release), keys to the focused view; a press focuses its view. In a
///   view in compare mode a press on the divider drags it, and a press elsewhere edits the
///   stack of that side;
/// - render priority: the views' sessions take turns on the worker pool (one RenderPassGate,
///   an edit preempting another view's refinement), updateRenderPriority() lets the focused
///   view refine first, and views
///   with linked cameras, which move together, share one frame's preview budget
///   (RenderSettings::previewBudgetSeconds divided among them).
///
/// A view's edit functions (Controller) work as in a Controller of its own; its history and
/// file functions (undo, saveSession, openScene, ...) act on the document.
/// Everything here runs on one thread (the UI thread).

#include <mvcl/core/Export.h>

#include <mvcl/controller/DocumentState.h>
#include <mvcl/controller/InputEvent.h>
#include <mvcl/controller/ViewRequest.h>
#include <mvcl/controller/ViewRouter.h>
#include <mvcl/core/Error.h>
#include <mvcl/io/SessionFile.h>
#include <mvcl/io/ViewLayout.h>
#include <mvcl/io/ViewLink.h>
#include <mvcl/view/RenderSettings.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mvcl {

class Controller;
class LensRegistry;
struct Scene;
class Tracer;

class MVCL_EXPORT Document {
public:
    /// Sets up as a Controller does (ViewSetup); a session file of several views gives one
    /// view each, with its links, layout, focus and compare stacks. The request's lenses and
    /// camera overrides go to the first view. Throws mvcl::Error when it cannot be set up.
    Document(const LensRegistry &registry, const ViewRequest &request, const RenderSettings &settings = {});
    ~Document();
    Document(const Document &) = delete;
    Document &operator=(const Document &) = delete;

    const LensRegistry &lensRegistry() const;
    const Scene &scene() const;
    const Tracer &tracer() const;

    // --- views --------------------------------------------------------------------------------------
    static constexpr int kMaxViews = 4;
    int viewCount() const;
    /// Throws mvcl::Error for an index outside 0..viewCount()-1.
    Controller &view(int index);
    const Controller &view(int index) const;
    /// A new view showing what the focused view shows (camera, layers, lenses; no compare
    /// stack), not linked. Returns its index; throws mvcl::Error past kMaxViews.
    int addView();
    int focusedView() const;
    Controller &focused() { return view(focusedView()); }
    /// Keys go to the focused view, and it renders first. Throws for a bad index.
    void setFocusedView(int index);

    // --- layout -------------------------------------------------------------------------------------
    ViewLayout layout() const;
    /// Adds views (addView) until the layout's cells are filled (also when a session is read);
    /// views beyond them are kept. The focus moves to a shown view.
    void setLayout(ViewLayout layout);
    /// The views the layout shows, one per cell in row-major order: views 0..cells-1, or the
    /// focused view alone in layout "1".
    std::vector<int> shownViews() const;

    // --- links --------------------------------------------------------------------------------------
    const std::vector<ViewLink> &links() const;
    bool isLinked(int a, int b, LinkAspect aspect) const;
    /// Links `aspect` of views a and b (one undo step) and copies it from the focused view if
    /// it is one of them, else from a. Throws mvcl::Error for a bad index or a == b.
    void link(int a, int b, LinkAspect aspect);
    void unlink(int a, int b, LinkAspect aspect);

    // --- input --------------------------------------------------------------------------------------
    /// Where the shown views are in the window (framebuffer pixels); resizes each view to its
    /// rectangle. The viewer calls it whenever the layout or the window changes.
    void setViewRects(const std::vector<ViewRect> &rects, float contentScale = 1.f);
    const ViewRouter &router() const;
    /// An event in window framebuffer pixels: routed (see the file comment) and applied.
    /// Returns true when some view's state changed. Resize events are setViewRects' business
    /// and are ignored here.
    bool handle(const InputEvent &event);
    /// The view being dragged by its compare divider, or -1.
    int dividerDragView() const;

    // --- files --------------------------------------------------------------------------------------
    SessionDescription description() const;
    /// Writes description() (version 1 for one plain view) and makes `file` the session path.
    void saveSession(const std::filesystem::path &file);
    /// Replaces the scene (when the file names another), the views, links, layout and focus
    /// with the file's, and starts a new history. A broken file throws mvcl::Error naming it
    /// and changes nothing.
    void loadSession(const std::filesystem::path &file);
    /// Opens other model files (several as layers) without blocking: a SceneLoadJob reads them
    /// and builds their tracer on a thread of its own while the views keep showing the current
    /// scene, and updateSceneLoad() installs its results. With the scene as read each view gets
    /// a fresh camera and every layer visible and keeps its lenses, links are applied again from
    /// the focused view, and the history starts anew; when the inferred layers follow, the views
    /// keep their cameras and lenses. A file that cannot be read goes to the error callback and
    /// the current scene stays. Opening again while one is in progress drops the earlier one.
    void openScenes(const std::vector<std::string> &sources, const SceneLoadOptions &options = {});
    /// Installs what the open in progress has ready. Call it once per UI frame; returns true
    /// when the scene changed (every view's renderSession() is then a new object).
    bool updateSceneLoad();
    bool isLoading() const;
    /// What the open in progress is doing ("reading body.glb", "inferring layers"), or empty.
    std::string loadProgress() const;
    /// Waits for the open in progress and installs its last result (scripts, tests).
    void finishSceneLoad();
    const std::filesystem::path &sessionPath() const;
    void setRecoveryPath(const std::filesystem::path &file);
    /// The path given, else "<session>.recovery.json" beside the session file, else none.
    std::filesystem::path recoveryPath() const;
    /// Writes the recovery copy now (the document calls it after every step).
    void writeRecovery();

    // --- history ------------------------------------------------------------------------------------
    void undo();
    void redo();
    bool canUndo() const;
    bool canRedo() const;
    int undoCount() const;
    int redoCount() const;
    /// The view the next undo step was made in, or -1.
    int undoView() const;
    /// Groups the edits of every view into one step until the matching endEditStep().
    void beginEditStep();
    void endEditStep();
    DocumentState state() const;

    // --- rendering ----------------------------------------------------------------------------------
    /// Starts (stops) every view's RenderSession on its own thread; views added later start too.
    void startRendering();
    void stopRendering();
    /// Holds the refinement of every view but the focused one while the focused one has work
    /// (RenderSession::setRefinementHeld). Call it once per UI frame.
    void updateRenderPriority();

    // --- notifications ------------------------------------------------------------------------------
    void setErrorCallback(std::function<void(const Error &)> callback);
    /// Called after another scene opened or views were added or removed: every view's
    /// renderSession() may be a new object then.
    void setViewsChangedCallback(std::function<void()> callback);

    struct MVCL_HIDDEN Private;

private:
    friend class Controller;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
