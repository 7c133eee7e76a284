#pragma once
/// \file Controller.h
/// The C of MVCL: the editable state of one view and the input that edits it, without a
/// window system. A Controller owns the view's RenderSession, the camera, the lens stack, the
/// visible layers and the selected lens, and shares the scene and tracer: a Controller made on
/// its own has them to itself, the views of a Document (Document.h) share the document's. Every
/// edit goes to the RenderSession at once, is one undo step, and reaches a recovery file within
/// a few seconds (RecoveryWriter);
/// in a document the history, the files and opening scenes are the document's (undo(),
/// saveSession(), openScene(), ... act on it), and links copy edits to other views.
///
/// The viewer turns window-system callbacks into InputEvents and calls handle(); panels call
/// the edit functions (addLens, setLensProperty, setLayerVisibility, ...). Everything here
/// runs on one thread (the UI thread); the RenderSession may render on its own thread
/// (renderSession().start()).
///
/// Key bindings of handle() (Ctrl is the Control modifier):
///
///     left drag on a 3D handle         edit the selected lens's box, sphere, plane, point or
///                                      rotation (Gizmo.h; with Shift: along an axis or the
///                                      view direction); wins over lenses, Shift-pan and orbit
///     left drag on a lens              move it (the lens under the pointer is selected)
///     left drag on a handle            resize the selected lens (corners, edge midpoints;
///                                      polygon vertices)
///     left drag elsewhere              orbit about the camera's target
///     middle drag, Shift + left drag   pan
///     scroll                           zoom toward the point under the pointer
///     left click on empty image        deselect
///     F, Home                          frame everything
///     1 … 6                            front, back, left, right, top, bottom view
///     keypad 1 / 3 / 7                 front / right / top (with Ctrl: back / left / bottom)
///     PageUp, PageDown                 raise, lower the selected lens
///     Delete, Backspace                delete the selected lens
///     Ctrl+D                           duplicate the selected lens
///     E                                enable or disable the selected lens
///     B                                fit the selected lens's box or sphere to the object under
///                                      the pointer (Shift+B: to everything)
///     P                                pin the selected lens to the pointer, or unpin it
///     Escape                           cancel the drag in progress, else deselect
///     Ctrl+Z                           undo
///     Ctrl+Shift+Z, Ctrl+Y             redo
///     a dropped .json file             load it as a session
///     dropped model files              open them, several as layers in the order given (the lens stack stays)
///     resize                           render at the new framebuffer size
///
/// Undo: every edit function and every gesture (press to release) is one step; a run of
/// scroll steps is merged into one. A step stores the whole editable state (SessionState)
/// before it, which undo() restores exactly. Opening another scene or loading a session
/// starts a new history.
///
/// Errors: edit functions throw mvcl::Error and leave the state as it was. Errors that have no
/// caller to go to — from handle() (a broken dropped file) and from writing the recovery copy —
/// go to the error callback; without one they are thrown.

#include <mvcl/core/Export.h>

#include <mvcl/controller/CameraNavigation.h>
#include <mvcl/controller/Gizmo.h>
#include <mvcl/controller/InputEvent.h>
#include <mvcl/controller/LensHandle.h>
#include <mvcl/controller/SessionState.h>
#include <mvcl/controller/ViewCoordinates.h>
#include <mvcl/controller/ViewRequest.h>
#include <mvcl/core/Error.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/RayPolicy.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/RenderSession.h>
#include <mvcl/view/RenderSettings.h>

#include <glm/vec2.hpp>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace mvcl {

class LensRegistry;
class Tracer;

enum class LayerVisibility : uint8_t { Visible, Hidden };

/// What is under a framebuffer position, as the pointer would grab it.
struct LensHit {
    enum class Target : uint8_t {
        Nothing, ///< the image: a drag orbits or pans
        Lens,    ///< the body of lens `lens`: a drag moves it
        Handle,  ///< `handle` of lens `lens`: a drag resizes it
        Gizmo,   ///< `gizmo`, a 3D handle of the selected lens `lens`: a drag edits its property
    };
    Target target = Target::Nothing;
    int lens = -1;
    LensHandle handle;
    GizmoHandle gizmo;
};

/// What fitLens() fits a lens's box or sphere to.
enum class LensFit : uint8_t {
    Object, ///< the mesh (or sphere) under a framebuffer position
    Layer,  ///< every mesh and sphere of one layer
    All,    ///< the whole scene
};

/// The gesture in progress.
enum class DragKind : uint8_t { None, MoveLens, ResizeLens, Orbit, Pan, Gizmo };

/// Which stack of a view in compare mode is being edited: left or right of the divider.
enum class CompareSide : uint8_t { Left, Right };

class Document;

class MVCL_EXPORT Controller {
public:
    /// Sets up the view as ViewSetup does (scene, camera, lenses, layer rules) at the size and
    /// with the sampling of `settings`, and builds the scene's tracer and RenderSession.
    /// A request naming a session file makes it the session path. Throws mvcl::Error when the
    /// request cannot be set up.
    Controller(const LensRegistry &registry, const ViewRequest &request, const RenderSettings &settings = {});
    ~Controller();
    Controller(const Controller &) = delete;
    Controller &operator=(const Controller &) = delete;

    // --- the scene -----------------------------------------------------------------------
    const Scene &scene() const;
    const Tracer &tracer() const;
    /// The view's renderer. It is replaced when another scene opens (see
    /// setSceneChangedCallback); a running one is stopped and its successor started.
    RenderSession &renderSession();
    /// The scene's model file or builtin:NAME; the first file when several are layered.
    const std::string &sceneSource() const;
    /// Every file of the scene, the outermost layer's first.
    std::vector<std::string> sceneSources() const;
    const SceneLoadOptions &sceneLoadOptions() const;
    /// Opens another scene with `options`: the lens stack stays, the camera is chosen afresh,
    /// every layer is visible again, and the history starts anew. On error nothing changes.
    /// A view of a Document opens without blocking (Document::openScenes: the scene appears
    /// with Document::updateSceneLoad()); a Controller of its own loads before it returns.
    void openScene(const std::string &source, const SceneLoadOptions &options = {});
    /// Opens several model files as the layers of one scene (loadScene(std::span)), as openScene.
    void openScenes(const std::vector<std::string> &sources, const SceneLoadOptions &options = {});

    // --- session files ---------------------------------------------------------------------
    /// The session as a file holds it: scene, camera in world units, layer rules, visible
    /// layers, lenses.
    LensStackDescription description() const;
    /// Writes description() atomically and makes `file` the session path.
    void saveSession(const std::filesystem::path &file);
    /// Replaces scene (when the file names another one or other layer rules), camera, visible
    /// layers and lenses with the file's, makes it the session path and starts a new history.
    /// A broken file throws mvcl::Error naming it and the problem and changes nothing.
    void loadSession(const std::filesystem::path &file);
    /// Empty until a session is loaded or saved.
    const std::filesystem::path &sessionPath() const;
    /// Where the recovery copy goes: the path given here, else "<session>.recovery.json" beside
    /// the session file, else nowhere. Every change of the state, drag moves included, goes to a
    /// RecoveryWriter: written atomically at most once per recoveryInterval(), the last change
    /// by updateRecovery() once the interval has passed. Saving the session removes the copy.
    void setRecoveryPath(const std::filesystem::path &file);
    std::filesystem::path recoveryPath() const;
    /// Least time between two writes of the recovery copy (RecoveryWriter::kDefaultInterval, 2 s);
    /// zero writes after every step.
    void setRecoveryInterval(std::chrono::milliseconds interval);
    std::chrono::milliseconds recoveryInterval() const;
    /// Once a frame: changes since the last call (drag moves) and a pending write that is due
    /// go to the recovery copy.
    void updateRecovery();
    /// At a clean exit: unsaved changes are written to the recovery copy now (the next start
    /// offers them); with none, the copy is removed.
    void finishRecovery();
    /// The state changed since the session was opened, loaded or saved.
    bool hasUnsavedChanges() const;
    /// A recovery copy newer than the session file, or of a session never saved: the last run
    /// ended with unsaved changes. Meant for the start, before any edit.
    bool hasRecovery() const;
    /// Loads the recovery copy as loadSession() does, but the session path and the recovery
    /// path stay as they were; the restored state is unsaved (the copy keeps it until the
    /// session is saved). Throws mvcl::Error for a broken copy and changes nothing.
    void restoreRecovery();
    /// Removes the recovery copy.
    void discardRecovery();
    /// "stack.json" → "stack.recovery.json".
    static std::filesystem::path defaultRecoveryPath(const std::filesystem::path &sessionFile);

    // --- view size and rendering -------------------------------------------------------------
    /// Framebuffer size of the view; the RenderSession renders at this size.
    glm::ivec2 viewSize() const;
    float contentScale() const;
    /// What a Resize event does.
    void resizeView(const glm::ivec2 &framebufferSize, float contentScale = 1.f);
    /// Sampling settings for the RenderSession; width and height follow the view size.
    void setRenderSettings(const RenderSettings &settings);
    RenderSettings renderSettings() const;
    ViewCoordinates coordinates() const;

    // --- camera (scene space) --------------------------------------------------------------------
    Camera camera() const;
    void setCamera(const Camera &camera);
    void orbit(float yawRadians, float pitchRadians);
    void pan(const glm::vec2 &pixelOffset);
    /// Zooms by `factor` (< 1 nearer) toward what is under the framebuffer position `pixel`.
    void zoomAt(const glm::vec2 &pixel, float factor);
    void frameAll();
    void setViewPreset(ViewPreset preset);
    /// The point the zoom keeps in place under `pixel`: the nearest visible hit, else the
    /// point on the pointer's ray at the target's depth.
    glm::vec3 pointUnder(const glm::vec2 &pixel) const;

    // --- layers -----------------------------------------------------------------------------------
    /// Throws mvcl::Error for a layer outside 0..31.
    void setLayerVisibility(int layer, LayerVisibility visibility);
    LayerVisibility layerVisibility(int layer) const;
    /// Bit i set: layer i is visible to primary rays outside every lens.
    uint32_t visibleLayers() const;
    /// Renames a layer of the scene in this view: one undo step, shown by layerName() (the
    /// scene itself, shared, keeps its names), saved in the session ("layerNames") and over
    /// every other source of names (rules, files, meshes). An
    /// empty name gives the layer back its name from the scene. Throws mvcl::Error for a layer
    /// the scene does not have or a name with a line break, and changes nothing.
    void setLayerName(int layer, const std::string &name);
    /// The layer's name as shown (empty for a layer the scene does not have).
    std::string layerName(int layer) const;
    void setVisibleLayers(uint32_t mask);
    /// The policy of pixels outside every lens, as given to the RenderSession.
    RayPolicy basePolicy() const;

    // --- lenses --------------------------------------------------------------------------------
    const LensRegistry &lensRegistry() const;
    /// The lenses as they render (committed). Edit them through the Controller only.
    const LensStack &lensStack() const;
    int lensCount() const;
    /// -1 when none is selected.
    int selectedLens() const;
    /// -1 deselects; selecting is not an edit step.
    void setSelectedLens(int index);
    /// A new lens of a registered type on its defaults, its region centred at `center`
    /// (normalised image coordinates), on top of the stack and selected. Returns its index.
    int addLens(std::string_view typeName, const glm::vec2 &center);
    /// A copy just above the lens, shifted by kDuplicateOffset, selected. Returns its index.
    int duplicateLens(int index);
    void removeLens(int index);
    /// Moves the lens at `from` to position `to` (0 = bottom); the selection follows it.
    void moveLens(int from, int to);
    void raiseLens(int index);
    void lowerLens(int index);
    void setLensEnabled(int index, bool enabled);
    void setLensLabel(int index, std::string label);
    void setLensRegion(int index, const LensRegion &region);
    /// Sets a declared property from its text form (PropertyDecl::parse). Throws mvcl::Error
    /// naming the lens and the property; the lens keeps its previous value.
    void setLensProperty(int index, std::string_view name, std::string_view text);
    /// The committed value in canonical text.
    std::string lensProperty(int index, std::string_view name) const;

    /// The topmost enabled lens whose coverage at `pixel` is > 0 or whose outline is under
    /// it; -1 for none.
    int lensAt(const glm::vec2 &pixel) const;
    /// A handle of the selected lens within grab distance of `pixel` wins over any lens body.
    LensHit hitTest(const glm::vec2 &pixel) const;
    /// Handles of a lens (normalised positions).
    std::vector<LensHandle> lensHandles(int index) const;
    /// How near (framebuffer pixels, before contentScale) a handle must be to be grabbed.
    static constexpr float kHandleGrabRadius = 6.f;

    // --- 3D handles (ControllerGizmos.cpp; the geometry is Gizmo.h's) --------------------------
    /// The gizmos of lens `index` whose properties are in use, in scene space; GizmoHandle::gizmo
    /// indexes this list.
    std::vector<GizmoShape> gizmoShapes(int index) const;
    /// The handles of lens `index` as they are drawn now.
    std::vector<GizmoHandle> gizmoHandles(int index) const;
    /// The camera and view size the handles are drawn in.
    GizmoView gizmoView() const;
    /// What the viewer draws for the selected lens (nothing when none is selected or it is
    /// disabled), with the handle under the pointer hovered and the dragged one active.
    GizmoDrawing gizmoDrawing() const;
    /// Drags the handle named `handle` (GizmoHandle::name) of lens `index`'s first gizmo by
    /// `offset` framebuffer pixels from where it is drawn, as a pointer would (one undo step);
    /// selects the lens. Throws mvcl::Error naming the lens when it has no such handle.
    void dragGizmoHandle(int index, std::string_view handle, const glm::vec2 &offset,
                         KeyModifier modifiers = KeyModifier::None);
    /// Sets lens `index`'s first box (else sphere) gizmo around `what`: the object under `pixel`,
    /// layer `layer`, or the whole scene (a box loses its rotation). One undo step. Throws
    /// mvcl::Error when the lens has no box or sphere, or there is nothing to fit to.
    void fitLens(int index, LensFit what, int layer = 0, const glm::vec2 &pixel = glm::vec2(0.f));
    /// Pins lens `index`'s region to the pointer: every pointer move that is not a drag centres
    /// the region there (not an undo step). −1 unpins. Only one lens follows at a time.
    void setPointerFollowingLens(int index);
    int pointerFollowingLens() const;
    /// Where a duplicate goes relative to its original (normalised).
    static constexpr float kDuplicateOffset = 0.03f;

    // --- compare mode (ControllerCompare.cpp) --------------------------------------------------------
    // The view split by a vertical divider: the lens stack left of it, a second stack right of
    // it, one camera. Turning it on copies the stack to the right side. The lens functions
    // above (lensStack(), addLens(), hitTest(), ...) act on the side being edited
    // (compareSide()); state() holds the left stack as `lenses` and the right one in
    // `compare`. Turning it on or off and moving the divider are edit steps; choosing the side
    // is not (like the selection).
    void setCompareEnabled(bool enabled);
    bool isCompareEnabled() const;
    /// Normalised x of the divider, 0..1 (0.5 when compare mode is off).
    float compareDivider() const;
    /// Clamped to 0..1; nothing when compare mode is off.
    void setCompareDivider(float x);
    CompareSide compareSide() const;
    /// Deselects when the side changes; nothing when compare mode is off.
    void setCompareSide(CompareSide side);
    /// The side of the divider `pixel` (framebuffer) is on; Left when compare mode is off.
    CompareSide compareSideAt(const glm::vec2 &pixel) const;
    /// Within grab distance (kHandleGrabRadius × contentScale) of the divider.
    bool isOnCompareDivider(const glm::vec2 &pixel) const;
    /// The stacks as they render (compare mode off: lensStack() and an empty one).
    const LensStack &leftLensStack() const;
    const LensStack &rightLensStack() const;

    // --- input ------------------------------------------------------------------------------------
    /// Applies an event. Returns true when the view's state changed (redraw the overlays).
    bool handle(const InputEvent &event);
    bool isDragging() const;
    DragKind dragKind() const;

    // --- history --------------------------------------------------------------------------------
    void undo();
    void redo();
    bool canUndo() const;
    bool canRedo() const;
    int undoCount() const;
    int redoCount() const;
    /// Groups edits into one step until the matching endEditStep() (e.g. a slider dragged in a
    /// panel); steps nest, and the outermost one counts.
    void beginEditStep();
    void endEditStep();
    /// The editable state now.
    SessionState state() const;

    // --- notifications -------------------------------------------------------------------------
    void setErrorCallback(std::function<void(const Error &)> callback);
    /// Called after another scene opened (renderSession() is a new object then).
    void setSceneChangedCallback(std::function<void()> callback);

private:
    friend class Document;
    /// A view of `document`'s open scene (Document.cpp).
    Controller(Document &document, int index, const Camera &camera, const RenderSettings &settings);

    struct MVCL_HIDDEN Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
