#pragma once
/// \file RenderSession.h
/// The interactive rendering engine of one view, without a window: it owns the accumulated
/// samples of every pixel, takes edits (camera, lens stack, base policy, settings) from any
/// thread between or during passes, and renders in passes that only do what changed:
///
/// - lens edits re-trace only the pixels whose composed policy (or blend weights) changed;
/// - a camera edit is followed by a reduced-resolution preview sized to a frame-time budget,
///   then full resolution, then refinement;
/// - refinement is progressive or adaptive (RenderSettings::sampling) until a sample, error or
///   time budget is reached; then the session is idle until the next edit.
///
/// Every edit cancels the pass in flight within about a millisecond (workers check once per
/// row). A cancelled pass keeps, per pixel, either all of its new samples or none of them.
/// Sample k of pixel (x, y) depends only on (x, y, k, seed), and a pixel's samples are summed in
/// order, so the accumulated image is the same for any thread count, and an incremental frame
/// equals a full re-render with the same samples bit for bit.
///
/// Passes run either on the caller's thread (renderPass(), for batch renders and tests) or on
/// a background thread (start()/stop(), for interactive views); the work itself runs on the
/// framework's worker pool.

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensRegion.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/lens/PolicyCost.h>
#include <mvcl/tracer/RayCounters.h>
#include <mvcl/tracer/RayPolicy.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/Framebuffer.h>
#include <mvcl/view/RenderSettings.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace mvcl {

class PolicyMap;
class Tracer;
struct RenderPassGate;

/// What a pass did.
enum class PassKind : uint8_t {
    Idle,    ///< nothing to do: the budget is reached and nothing changed
    Preview, ///< camera moved: one sample per block of divider × divider pixels, display only
    Full,    ///< every pixel restarted (first pass, camera or settings changed)
    Retrace, ///< lens or base-policy edit: only pixels whose policy changed restarted
    Refine,  ///< more samples for pixels below their budget (progressive or adaptive)
};

MVCL_EXPORT const char *passKindName(PassKind kind);

struct RenderPassStats {
    PassKind kind = PassKind::Idle;
    bool wasCancelled = false;   ///< an edit (or the time limit) stopped it early
    int resolutionDivider = 1;   ///< Preview: block size in pixels
    uint64_t pixelsRestarted = 0; ///< pixels whose samples were dropped by this pass's edits
    uint64_t pixelsTraced = 0;   ///< pixels (blocks for a preview) that got samples
    uint64_t samples = 0;        ///< pixel samples taken (one per blended policy term)
    RayCounters rays;
    double composeMilliseconds = 0.0; ///< composing and comparing the lens policies
    double traceMilliseconds = 0.0;   ///< tracing (wall clock)
    double milliseconds = 0.0;        ///< the whole pass (wall clock)
    PixelRect updated;                ///< bounding box of the display pixels this pass changed
    std::vector<PolicyCost> perPolicy; ///< cost per entry of policyMap() (same index)
    std::vector<LensCost> perLens;     ///< cost of the pixels under each lens of the stack
};

/// The state of the accumulated image (not of a preview on display).
struct ConvergenceStats {
    int minSamples = 0;
    double meanSamples = 0.0;
    int maxSamples = 0;
    double meanError = 0.0; ///< mean over pixels with ≥ 2 samples of the per-pixel estimate
    double maxError = 0.0;
    /// The image's relMSE (mean over pixels and channels of (I − R)² / (R² + 0.01), R the
    /// converged image) as estimated without R: per pixel, the variance of its mean from the
    /// differences of the means of contiguous runs of its samples, scaled per sample count to
    /// the expected squared error (docs/architecture.md, "The render session"); under adaptive
    /// sampling from runs its decisions did not look at. Empty until every pixel has two samples.
    std::optional<double> estimatedRelativeMse;
    uint64_t activePixels = 0; ///< pixels that still want samples
    double elapsedSeconds = 0.0; ///< since the last reset of every pixel
    bool isConverged = false;    ///< no pixel wants samples: the session is idle
};

class MVCL_EXPORT RenderSession {
public:
    /// The tracer (and its scene) must outlive the session.
    explicit RenderSession(const Tracer &tracer);
    ~RenderSession(); ///< stops the background thread
    RenderSession(const RenderSession &) = delete;
    RenderSession &operator=(const RenderSession &) = delete;

    // Edits: callable from any thread, at any time; each cancels the pass in flight.
    void setCamera(const Camera &camera);
    /// Copies the stack's list of lenses. The session reads the lenses' committed snapshots at
    /// the start of each pass; after committing a lens of the stack, call setLensStack again so
    /// that an idle or background session looks.
    void setLensStack(const LensStack &stack);
    /// Compare mode: `left` renders left of the divider, `right` right of it, both under the
    /// same camera and base policy. `dividerX` is the divider's normalised x (0..1); pixel
    /// columns x < round(dividerX · width) are left's. Moving the divider re-traces only the
    /// pixels between the old and the new column whose policies differ between the stacks.
    /// setLensStack() ends compare mode. Per-lens costs (RenderPassStats::perLens) list the
    /// left stack's lenses, then the right's.
    void setLensStacks(const LensStack &left, const LensStack &right, float dividerX);
    /// The policy of pixels outside every lens (layer visibility, shading defaults).
    void setBasePolicy(const RayPolicy &policy);
    /// Size, seed and tile changes restart every pixel; sampling budgets keep the samples.
    void setSettings(const RenderSettings &settings);
    RenderSettings settings() const;
    Camera camera() const;

    /// Called during passes with the fraction (0..1) of the pass's tiles done, from worker
    /// threads, serialised. Set it before passes run.
    void setProgressCallback(std::function<void(float)> callback);

    /// Runs one pass on the calling thread (its work on the worker pool). Returns at once with
    /// kind Idle when there is nothing to do. Not to be mixed with start().
    RenderPassStats renderPass();
    /// Runs passes until the session is idle; returns the passes' stats summed (kind: the last
    /// pass's).
    RenderPassStats renderUntilIdle();
    /// renderUntilIdle(), calling `afterPass` with each pass's own stats as it ends (a
    /// ConvergenceLog row, a progress line), on the calling thread.
    RenderPassStats renderUntilIdle(const std::function<void(const RenderPassStats &)> &afterPass);
    /// True when the next pass would do something.
    bool hasWork() const;

    /// Starts a background thread that runs passes whenever there is work and sleeps otherwise.
    void start();
    /// Cancels the pass in flight and joins the background thread.
    void stop();
    bool isRunning() const;
    /// While held, the session runs only the passes its edits ask for (preview, full
    /// resolution, retrace); more samples for an image already complete at full resolution
    /// wait until it is released. Sessions that share the worker pool use it to let one of
    /// them (the focused view of several) refine first.
    void setRefinementHeld(bool held);
    bool isRefinementHeld() const;
    /// Sessions given one gate (makePassGate()) run their background passes one at a time, so
    /// that together they keep to the worker pool's threads instead of each adding a thread of
    /// its own (the views of a Document share one). An edit of one session cancels another's
    /// pass that only refines (its finished pixels are kept; it runs again afterwards), so edits
    /// do not wait behind refinement. Set it before start().
    void setPassGate(std::shared_ptr<RenderPassGate> gate);
    static std::shared_ptr<RenderPassGate> makePassGate();
    /// Stats of the last finished pass (any thread).
    RenderPassStats lastPass() const;
    /// Number of passes finished since construction (any thread).
    uint64_t passCount() const;

    /// The image on display: the accumulated mean of every pixel, or a preview while the camera
    /// moves. For the thread that runs the passes (renderPass) only; other threads use
    /// copyImage.
    const Framebuffer &image() const;
    /// Any thread: copies the display pixels changed since this caller's last copy into
    /// `target` (resized, and then fully copied, when its size differs) and sets `changed` to
    /// their bounding box. Never waits: returns false without copying when a pass is
    /// publishing at that moment.
    bool copyImage(Framebuffer &target, PixelRect &changed);

    /// The accumulated state as of the end of the last pass (any thread).
    ConvergenceStats convergence() const;
    /// Per-pixel sample counts and estimated errors of the accumulated image (row-major; the
    /// thread that runs the passes, or after stop()).
    std::vector<uint32_t> sampleCounts() const;
    std::vector<float> errorEstimates() const;
    /// Per pixel, the rays its accumulated samples cost (row-major, as sampleCounts()):
    /// adaptive sampling serves the pixels whose estimate² over these rays is highest.
    std::vector<uint32_t> rayCounts() const;
    /// The policy map the accumulated samples were taken under.
    const PolicyMap &policyMap() const;

private:
    struct MVCL_HIDDEN Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
