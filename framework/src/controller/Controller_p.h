#pragma once
// The state behind Controller's d-pointer, shared by the Controller*.cpp files.

#include <mvcl/controller/Controller.h>
#include <mvcl/controller/RecoveryWriter.h>
#include <mvcl/controller/ViewSetup.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
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
        Camera startCamera;
        Step start; ///< restored by Escape
    };

    Controller &q; ///< the public object, for input that maps onto its edit functions
    const LensRegistry &registry;

    // The open scene. Declared in this order so that the session dies before the tracer it
    // renders with, and the tracer before the scene it points into.
    ViewSetup setup; ///< source and load options (its session part is not kept)
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Tracer> tracer;
    std::unique_ptr<RenderSession> session;

    RenderSettings settings;
    glm::ivec2 viewSize{800, 600};
    float contentScale = 1.f;

    // The editable state.
    Camera camera;
    uint32_t visibleLayers = kAllLayers;
    std::map<int, std::string> layerNames;      ///< renamed layers (setLayerName)
    std::map<int, std::string> sceneLayerNames; ///< the scene's own names, as loaded
    LensStack stack;
    int selected = -1;

    // History.
    std::vector<Step> undoSteps;
    std::vector<Step> redoSteps;
    int openSteps = 0;
    Step openStepStart;
    StepKind lastStep = StepKind::Other;

    Drag drag;

    LensContext sceneContext;            ///< the scene part of placeLenses()'s context
    const Scene *sceneOfContext = nullptr; ///< the scene it was computed for

    std::filesystem::path sessionPath;
    std::filesystem::path explicitRecoveryPath;
    RecoveryWriter recovery;
    bool stateTouched = false;    ///< send*() ran since the recovery writer last heard of it
    bool unsaved = false;         ///< the state changed since the session was loaded or saved
    std::string lastRecoveryError; ///< reported once, not at every retry
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
    }
    void sendLenses() {
        stateTouched = true;
        placeLenses();
        session->setLensStack(stack);
        reportLensFaults();
    }
    /// Tells the error callback, once per lens and fault, about every lens of the stack that
    /// its plugin's fault disabled (Lens::fault). Nothing without a callback: setErrorCallback
    /// reports what is there by then.
    void reportLensFaults();
    std::map<const Lens *, std::string> reportedFaults;
    void sendBasePolicy() {
        stateTouched = true;
        session->setBasePolicy(basePolicy());
    }
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
        if (openSteps > 0) {
            apply();
            return;
        }
        const Step before = captureStep();
        apply();
        finishStep(before, kind);
    }
    /// Takes over a newly loaded scene; stops and replaces the RenderSession.
    void replaceScene(std::unique_ptr<Scene> newScene, std::unique_ptr<Tracer> newTracer);

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
