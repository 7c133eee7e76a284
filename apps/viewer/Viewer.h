#pragma once
// The viewer's state between frames: the document (scene, views, links, history), each view's
// image texture, the panels' bits of UI state and the script being replayed. The panels and
// the script's lens commands act on the focused view (m_controller).
// main.cpp calls update(), drawUi() and frameDrawn() once per frame.

#include "ImageTexture.h"
#include "ViewerOptions.h"
#include "ViewerScript.h"

#include <mvcl/controller/AnimationPlayer.h>
#include <mvcl/controller/Controller.h>
#include <mvcl/controller/Document.h>
#include <mvcl/controller/ViewRecorder.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/lens/PolicyMap.h>
#include <mvcl/view/ConvergenceHistory.h>
#include <mvcl/view/DepthHistogram.h>
#include <mvcl/view/Framebuffer.h>
#include <mvcl/view/Picking.h>

#include <array>
#include <chrono>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

struct GLFWwindow;

namespace mvcl::viewer {

class Viewer {
public:
    Viewer(GLFWwindow *window, const ViewerOptions &options);
    ~Viewer();
    Viewer(const Viewer &) = delete;
    Viewer &operator=(const Viewer &) = delete;

    /// Takes the window system's events. While a model opens and its first image is not yet
    /// on screen, waits up to a tenth of a second for input or for the load's next step instead
    /// of drawing as fast as it can: nothing but the progress line changes meanwhile, and with
    /// software OpenGL (and the X server's share) a frame of the whole window costs a core some
    /// 20 ms that the load needs.
    void pollEvents();
    /// Before the UI frame: replays the script, takes the render session's new pixels.
    void update();
    /// Inside the ImGui frame: the image, lens overlays, panels; forwards input to the controller.
    void drawUi();
    /// After the frame is drawn, before it is shown: window screenshots, frame timing.
    void frameDrawn();

    bool wantsToQuit() const { return m_quit; }
    int exitCode() const { return m_exitCode; }

private:
    using Clock = std::chrono::steady_clock;

    // Viewer.cpp
    void layout();
    void takeImage();
    /// Starts opening model files (the document loads them on a thread of its own).
    void startOpening(const std::vector<std::string> &files);
    /// Installs what the open in progress has ready and says how long it took.
    void updateOpening();
    void forwardInput();
    void handleViewerKeys();
    /// An event at the focused view's framebuffer pixels (the script's), to the document.
    void handle(const InputEvent &event);
    /// An event at window framebuffer pixels, to the document (routed to a view).
    void handleInWindow(const InputEvent &event);
    void report(const std::string &message);
    void writeScreenshot(const std::string &file);
    void saveSession(const std::string &file);
    void openFile(const std::string &file);
    // ViewerViews.cpp (drawViewOverlays is in ViewerOverlays.cpp)
    /// Places the shown views in the image area (the layout's grid) and tells the document.
    void layoutViews();
    /// The focused view again (after a press, undo, a layout change, a session load).
    void refocus();
    void setLayout(ViewLayout layout);
    /// What every view would show as laid out, without UI (the script's screenshot).
    Framebuffer composedViews() const;
    /// A thin frame around the focused view when several are shown.
    void drawViewFrames();
    /// One view's lens outlines, handles and compare divider, clipped to the view: everything
    /// drawn for a view is a function of its controller and its place on screen.
    void drawViewOverlays(const Controller &view, const glm::vec2 &origin, const glm::vec2 &size);
    // ViewerOverlays.cpp
    void drawImage();
    void drawLensOverlays();
    void drawFitButtons(int lensIndex); ///< ViewerPanels.cpp
    int m_fitLayer = 0;                 ///< the panel's "fit to layer" choice
    void drawHelpOverlay();
    void drawMessages();
    // ViewerPanels.cpp
    void drawPanels();
    /// Layout, links of the focused view, compare mode.
    void drawViewsPanel();
    void drawLensStackPanel();
    void drawLensPanel();
    void drawLayersPanel();
    void drawStatsPanel();
    void drawConvergenceCurve();
    void drawPickPanel();
    void drawHistogramPanel();
    /// Joins the histogram worker: before anything replaces the scene it traces.
    void stopHistogramWorker();
    const PolicyMap &pickingMap();
    void drawOpenPopup();
    template <class Edit> void edit(Edit &&edit);
    // ViewerAnimation.cpp
    void drawAnimationPanel();
    /// Adds the camera and the selected lens at `seconds` to the animation file (made if missing).
    void addKeyframe(const std::string &file, double seconds);
    /// mvcl-render's --turntable and --sweep as a file: one turn in `turntableFrames` frames
    /// (none if 0) and the sweep `sweepSpec` (LENS.PROPERTY=FROM:TO; none if empty).
    void writeShortcutAnimation(const std::string &file, int turntableFrames, const std::string &sweepSpec);
    void startPlaying(const std::string &file);
    /// Shows the animation's time on the view (lenses and camera to the render session, no edit).
    void updatePlayback();
    void stopPlaying();
    void startRecording(const std::string &target, double frameRate);
    /// Hands the view's image (lens outlines, no panels) to the recorder.
    void recordFrame();
    void stopRecording();
    // ViewerRecovery.cpp
    /// At start: a recovery copy newer than its session (or of a session never saved) means the
    /// last run ended before saving; a modal offers to restore or discard it.
    void offerRecovery();
    void drawRecoveryOffer();
    void answerRecoveryOffer(bool restore);
    // ViewerScripting.cpp
    void runScript();
    bool runCommand(const ScriptCommand &command);

    GLFWwindow *m_window;
    ViewerOptions m_options;
    LensRegistry m_registry;
    std::unique_ptr<Document> m_document;
    Controller *m_controller = nullptr; ///< the focused view of m_document

    /// What the window shows of one view.
    struct ViewDisplay {
        ImageTexture texture;
        Framebuffer image;          ///< the last copy of the session's display image
        bool current = false;       ///< `image` holds everything the session has published
        bool shown = false;         ///< the layout shows the view
        glm::vec2 screenOrigin{0.f}; ///< screen units (ImGui's)
        glm::vec2 screenSize{1.f};
        glm::ivec2 pixelOrigin{0};  ///< window framebuffer pixels
    };
    std::array<ViewDisplay, Document::kMaxViews> m_views;
    ViewDisplay &focusedDisplay() { return m_views[std::size_t(m_document->focusedView())]; }

    // Layout in screen units (ImGui's) and framebuffer pixels.
    float m_contentScale = 1.f;
    glm::vec2 m_framebufferScale{1.f};
    glm::vec2 m_viewScreenSize{0.f}; ///< the image area, every view together
    float m_panelWidth = 0.f;

    // UI state.
    bool m_showHelp = false;
    bool m_editStepOpen = false;      ///< a panel widget is being dragged: one undo step
    bool m_openPopupRequested = false;
    bool m_recoveryOffered = false;   ///< the Restore / Discard modal is waiting for an answer
    std::string m_openPath;
    std::deque<std::string> m_messages;
    glm::vec2 m_pointer{-1.f};        ///< framebuffer pixels of the focused view; negative when outside it
    int m_screenshotCount = 0;
    std::string m_pendingWindowShot;

    // Picking: a policy map of our own (the session's belongs to its render thread), composed
    // again when a lens snapshot or the view size changes.
    std::optional<PolicyMap> m_pickMap;
    std::vector<const void *> m_pickSnapshots;
    uint32_t m_pickLayers = 0;

    // Depth histogram of the selected layer lens, computed off the UI thread.
    std::jthread m_histogramWorker;
    std::mutex m_histogramMutex;
    std::optional<DepthHistogram> m_histogram; ///< under m_histogramMutex
    int m_histogramLens = -1;
    bool m_histogramBusy = false;             ///< under m_histogramMutex

    // Frame timing.
    Clock::time_point m_frameStart = Clock::now();
    double m_lastFrameMs = 0.0;
    std::deque<double> m_frameTimes;
    ConvergenceHistory m_convergence; ///< the focused view's estimated error against time

    // Animation: keyframes into a file, playback on the view, recording of what the view shows.
    std::string m_animationFile = "animation.json";
    float m_keyframeSeconds = 0.f;
    int m_turntableFrames = 60;
    std::string m_sweepSpec;
    std::optional<AnimationPlayer> m_player; ///< while playing
    Clock::time_point m_playStart;
    int m_playScriptLine = -1; ///< the script's play command that started the playback
    std::string m_recordTarget = "out/recording/%04d.png";
    float m_recordFrameRate = 30.f;
    std::optional<ViewRecorder> m_recorder; ///< while recording
    Clock::time_point m_recordStart;

    // Opening files without blocking (Document::openScenes): when the open started, and
    // whether the new scene's first image is still to be reported.
    Clock::time_point m_openStart;
    const Scene *m_openShownScene = nullptr; ///< the scene the last load result showed
    bool m_openShowedScene = false; ///< the open in progress has put its scene on screen
    bool m_awaitingFirstImage = false;

    // Script replay.
    std::optional<ViewerScript> m_script;
    int m_waitFrames = 0;
    bool m_scriptOpenStarted = false; ///< `open` runs until the load is done
    int m_dragStep = -1;
    std::string m_benchName;
    std::vector<double> m_benchFrames;
    uint64_t m_benchImageUpdates = 0;
    bool m_quit = false;
    int m_exitCode = 0;
};

} // namespace mvcl::viewer
