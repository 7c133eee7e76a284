#pragma once
// The state behind Controller's d-pointer, shared by the Controller*.cpp files.

#include <mvcl/controller/Controller.h>
#include <mvcl/controller/Document.h>
#include <mvcl/controller/RecoveryWriter.h>
#include <mvcl/controller/ViewSetup.h>
#include <mvcl/io/ViewLink.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <optional>
#include <vector>

namespace mvcl {

struct Controller::Private {
    Private(Controller &owner, const LensRegistry &lensRegistry) : q(owner), registry(lensRegistry) {}

    /// What an undo step restores: the state, and which lens was selected with it.
    struct Step {
        SessionState state;
        int selected = -1;
    };
    /// Steps of this kind in a row merge into one (a run of scroll-wheel zooms).
    enum class StepKind : uint8_t { Other, Zoom };
    static constexpr std::size_t kMaxUndoSteps = 1000;

    struct Drag {
        DragKind kind = DragKind::None;
        PointerButton button = PointerButton::None;
        glm::vec2 pressPosition{0.f};
        bool hasMoved = false;
        int lens = -1;
        LensHandle handle;
        LensRegion startRegion;
        GizmoHandle gizmo;      ///< DragKind::Gizmo
        GizmoShape gizmoStart;  ///< DragKind::Gizmo
        Camera startCamera;
        Step start; ///< restored by Escape
    };

    Controller &q; ///< the public object, for input that maps onto its edit functions
    const LensRegistry &registry;

    // The open scene, shared by every view of a Document. Declared in this order so that the
    // session dies before the tracer it renders with, and the tracer before the scene it
    // points into.
    ViewSetup setup; ///< source and load options (its session part is not kept)
    std::shared_ptr<const Scene> scene;
    std::shared_ptr<const Tracer> tracer;
    std::unique_ptr<RenderSession> session;

    /// The document this view belongs to, or none (a Controller of its own, as mvcl-render and
    /// the one-view tests make it). With one, the history, the files and opening scenes are the
    /// document's, and every change of camera, lenses or layers is told to it (links).
    Document::Private *document = nullptr;
    int viewIndex = 0;

    /// Compare mode: the stack that is not being edited and the divider. `stack` is always the
    /// stack being edited (left or right of the divider, `side`), so the lens edits and input
    /// work on either side unchanged.
    struct Compare {
        LensStack other;
        float divider = 0.5f;
        CompareSide side = CompareSide::Left;
    };
    std::optional<Compare> compare;
    const LensStack &leftStack() const { return compare && compare->side == CompareSide::Right ? compare->other : stack; }
    const LensStack &rightStack() const { return compare->side == CompareSide::Right ? stack : compare->other; }

    RenderSettings settings;
    glm::ivec2 viewSize{800, 600};
    float contentScale = 1.f;

    // The editable state.
    Camera camera;
    uint32_t visibleLayers = kAllLayers;
    std::map<int, std::string> layerNames;      ///< renamed layers (setLayerName)
    LensStack stack;
    int selected = -1;

    // History.
    std::vector<Step> undoSteps;
    std::vector<Step> redoSteps;
    int openSteps = 0;
    Step openStepStart;
    StepKind lastStep = StepKind::Other;

    Drag drag;
    std::optional<GizmoHandle> hoveredGizmo; ///< of the selected lens, under the pointer
    glm::vec2 pointer{-1.f};                ///< the pointer's last position (framebuffer px)
    std::weak_ptr<const Lens> pointerFollower; ///< setPointerFollowingLens: follows the lens, not its index
    int followerIndex() const;

    LensContext sceneContext;            ///< the scene part of placeLenses()'s context
    const Scene *sceneOfContext = nullptr; ///< the scene it was computed for

    std::filesystem::path sessionPath;
    std::filesystem::path explicitRecoveryPath;
    RecoveryWriter recovery;      ///< a Controller of its own; a document's views use the document's
    RecoveryWriter &recoveryWriter();
    bool stateTouched = false;    ///< send*() ran since the recovery writer last heard of it
    bool unsaved = false;         ///< the state changed since the session was loaded or saved
    std::function<void(const Error &)> errorCallback;
    std::function<void()> sceneChangedCallback;

    // --- helpers (Controller.cpp) ---
    ViewCoordinates coordinates() const { return ViewCoordinates(viewSize, *scene); }
    RayPolicy basePolicy() const;
    SessionState captureState() const;
    Step captureStep() const { return {captureState(), selected}; }
    /// Makes `step` the current state and tells the RenderSession what changed.
    void restore(const Step &step);
    /// Gives every lens of the stack the scene and view it is shown in, and recommits those
    /// whose contribution that changes (LensContext), so that their snapshots (picking, files)
    /// agree with the image. A lens that cannot commit in the new context keeps its snapshot.
    void placeLenses();
    // Every change of the session state goes through these three, drag moves included; they
    // mark it for the recovery copy (passRecovery).
    void sendCamera() {
        stateTouched = true;
        placeLenses();
        session->setCamera(camera);
        tellDocument(LinkAspect::Camera);
    }
    void sendLenses();
    /// Tells the error callback, once per lens and fault, about every lens of the stack that
    /// its plugin's fault disabled (Lens::fault). Nothing without a callback: setErrorCallback
    /// reports what is there by then.
    void reportLensFaults();
    std::map<const Lens *, std::string> reportedFaults;
    void sendBasePolicy() {
        stateTouched = true;
        session->setBasePolicy(basePolicy());
        tellDocument(LinkAspect::Layers);
    }
    /// Tells the document (if any) that this view's `aspect` changed, for its links.
    void tellDocument(LinkAspect aspect);
    /// `stack` rebuilt to hold `wanted`, reusing its lenses that are already in a wanted
    /// state; throws (changing nothing) when a lens cannot be built.
    LensStack rebuiltStack(const LensStack &current, const std::vector<LensState> &wanted) const;
    RenderSettings sessionSettings() const;
    /// Ends an edit that started at `before`: one undo step if anything changed; the change
    /// goes to the recovery writer.
    void finishStep(const Step &before, StepKind kind);
    void clearHistory();
    /// Tells the recovery writer about changes since the last call (it writes when due) and
    /// gives it a pending write that is due. Called after every edit step and once a frame
    /// (Controller::updateRecovery); a failed write goes to the error callback, once.
    void passRecovery();
    /// The state as it is now is the session file's (loaded or saved): nothing to recover.
    void markSaved();
    /// The error callback, or a throw without one.
    void report(const Error &error) const;
    /// Runs `apply` as one step (or as part of the open one).
    template <class Apply> void edit(StepKind kind, Apply &&apply) {
        if (document) {
            editInDocument(kind, apply);
            return;
        }
        if (openSteps > 0) {
            apply();
            return;
        }
        const Step before = captureStep();
        apply();
        finishStep(before, kind);
    }
    /// edit() in a view of a document: the document's history (Document_p.h).
    void editInDocument(StepKind kind, const std::function<void()> &apply);
    /// Takes over a newly loaded scene; stops and replaces the RenderSession.
    void replaceScene(std::shared_ptr<const Scene> newScene, std::shared_ptr<const Tracer> newTracer);

    // --- layer names (ControllerLayerNames.cpp) ---
    /// Takes `names` as the renamed layers and shows them in the scene's layer table.
    void setLayerNames(std::map<int, std::string> names);

    // --- lenses (ControllerLenses.cpp) ---
    /// Throws mvcl::Error for an index outside the stack.
    Lens &lens(int index) const;
    /// "lens 2 'reveal' (layer)", the source of errors about that lens.
    std::string lensName(int index) const;
    /// `region` moved by `offset` (normalised).
    static LensRegion translatedRegion(const LensRegion &region, const glm::vec2 &offset);
    /// Stages `region` on lens `index` and commits it; restores the lens on error.
    void commitRegion(int index, const LensRegion &region);

    /// The hit the pixel shows (the lenses over it shape its ray and limit what it may hit);
    /// `shot` gets the ray.
    std::optional<Hit> hitUnder(const glm::vec2 &pixel, Ray *shot = nullptr) const;

    // --- 3D handles (ControllerGizmos.cpp) ---
    /// The selected lens's handle under `pixel`, if any.
    std::optional<GizmoHandle> gizmoAt(const glm::vec2 &pixel) const;
    /// Starts a gizmo drag of `handle` of lens `index` at `pixel` (one edit step until release).
    void startGizmoDrag(int index, const GizmoHandle &handle, const glm::vec2 &pixel, PointerButton button);
    /// The open gizmo drag with the pointer at `pixel`.
    void moveGizmo(const glm::vec2 &pixel, KeyModifier modifiers);
    /// A pointer move that is not a drag: the hovered handle, a lens that follows the pointer.
    /// True when something to draw changed.
    bool hover(const glm::vec2 &pixel);

    // --- input (ControllerInput.cpp) ---
    bool pointerPress(const InputEvent &event);
    bool pointerMove(const InputEvent &event);
    bool pointerRelease(const InputEvent &event);
    bool scroll(const InputEvent &event);
    bool keyPress(const InputEvent &event);
    bool fileDrop(const InputEvent &event);
    void cancelDrag();
};

} // namespace mvcl
