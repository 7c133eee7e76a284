// Replaying a --script file: pointer and key events go to the controller exactly as the
// window's would; commands wait for the render session, write images and sessions, and time
// UI frames. One pointer event per frame, so a scripted drag renders like a real one.

#include "Viewer.h"
#include "ViewerGizmos.h"

#include <mvcl/core/Error.h>
#include <mvcl/view/RenderSession.h>

#include <algorithm>
#include <cstdio>
#include <map>

namespace mvcl::viewer {

namespace {

PointerButton buttonNamed(const ScriptCommand &c, const std::string &name) {
    if (name == "left") return PointerButton::Left;
    if (name == "middle") return PointerButton::Middle;
    if (name == "right") return PointerButton::Right;
    throw Error("script line " + std::to_string(c.line), c.name + ": unknown button '" + name + "' (left, middle, right)");
}

} // namespace

void Viewer::runScript() {
    if (!m_script || m_quit) return;
    try {
        // Commands run until one needs a frame drawn (pointer events, waits). The script ends
        // after its last command's frames: a closing wait-frames waits too.
        while (!m_quit) {
            if (m_waitFrames > 0) {
                --m_waitFrames;
                return;
            }
            if (m_script->isFinished()) {
                m_quit = true;
                return;
            }
            if (!runCommand(m_script->current())) return; // not done yet: again next frame
            m_script->advance();
        }
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-viewer: %s: %s\n", m_script->file().string().c_str(), e.what());
        m_exitCode = 1;
        m_quit = true;
    }
}

bool Viewer::runCommand(const ScriptCommand &c) {
    const std::string &name = c.name;
    auto fail = [&](const std::string &problem) -> bool {
        throw Error("script line " + std::to_string(c.line), name + ": " + problem);
    };
    if (name == "move") {
        m_pointer = {float(c.number(0)), float(c.number(1))};
        handle(InputEvent::pointerMove(m_pointer));
        m_waitFrames = 1;
    } else if (name == "press" || name == "release") {
        const PointerButton button = buttonNamed(c, c.word(0));
        handle(name == "press" ? InputEvent::pointerPress(m_pointer, button, c.modifiers())
                               : InputEvent::pointerRelease(m_pointer, button, c.modifiers()));
        m_waitFrames = 1;
    } else if (name == "click") {
        const PointerButton button = buttonNamed(c, c.word(0));
        m_pointer = {float(c.number(1)), float(c.number(2))};
        handle(InputEvent::pointerMove(m_pointer));
        handle(InputEvent::pointerPress(m_pointer, button, c.modifiers()));
        handle(InputEvent::pointerRelease(m_pointer, button, c.modifiers()));
        m_waitFrames = 1;
    } else if (name == "drag") {
        // Spread over frames: press, N moves, release; m_dragStep counts where we are.
        const PointerButton button = buttonNamed(c, c.word(0));
        const glm::vec2 from(float(c.number(1)), float(c.number(2))), to(float(c.number(3)), float(c.number(4)));
        const int steps = c.args.size() > 5 && c.args[5] != "shift" && c.args[5] != "ctrl" && c.args[5] != "alt"
                              ? std::max(1, c.integer(5))
                              : 8;
        if (m_dragStep < 0) {
            m_pointer = from;
            handle(InputEvent::pointerMove(m_pointer, c.modifiers()));
            handle(InputEvent::pointerPress(m_pointer, button, c.modifiers()));
            m_dragStep = 0;
            return false;
        }
        if (m_dragStep < steps) {
            ++m_dragStep;
            m_pointer = from + (to - from) * (float(m_dragStep) / float(steps));
            handle(InputEvent::pointerMove(m_pointer, c.modifiers()));
            return false;
        }
        handle(InputEvent::pointerRelease(m_pointer, button, c.modifiers()));
        m_dragStep = -1;
        m_waitFrames = 1;
    } else if (name == "scroll") {
        if (c.args.size() == 3) m_pointer = {float(c.number(1)), float(c.number(2))};
        handle(InputEvent::scrolled(m_pointer, {0.f, float(c.number(0))}));
        m_waitFrames = 1;
    } else if (name == "key") {
        static const std::map<std::string, Key> kKeys = {
            {"1", Key::Digit1}, {"2", Key::Digit2}, {"3", Key::Digit3}, {"4", Key::Digit4}, {"5", Key::Digit5},
            {"6", Key::Digit6}, {"F", Key::F}, {"E", Key::E}, {"D", Key::D}, {"Z", Key::Z}, {"Y", Key::Y},
            {"Home", Key::Home}, {"PageUp", Key::PageUp}, {"PageDown", Key::PageDown}, {"Delete", Key::Delete},
            {"Backspace", Key::Backspace}, {"Escape", Key::Escape}, {"B", Key::B}, {"P", Key::P},
        };
        const std::string &key = c.word(0);
        if (key == "F1") m_showHelp = !m_showHelp;
        else if (key == "F12") writeScreenshot("out/mvcl-viewer-" + std::to_string(++m_screenshotCount) + ".png");
        else if (const auto it = kKeys.find(key); it != kKeys.end()) handle(InputEvent::keyPress(it->second, c.modifiers()));
        else fail("unknown key '" + key + "'");
        m_waitFrames = 1;
    } else if (name == "add-lens") {
        m_controller->addLens(c.word(0), {float(c.number(1)), float(c.number(2))});
    } else if (name == "select") {
        m_controller->setSelectedLens(c.integer(0));
    } else if (name == "set-property") {
        m_controller->setLensProperty(c.integer(0), c.word(1), c.word(2));
    } else if (name == "set-layer") {
        if (c.word(1) != "visible" && c.word(1) != "hidden") fail("expects visible or hidden");
        m_controller->setLayerVisibility(c.integer(0), c.word(1) == "visible" ? LayerVisibility::Visible : LayerVisibility::Hidden);
    } else if (name == "set-layer-name") {
        m_controller->setLayerName(c.integer(0), c.word(1));
    } else if (name == "recovery") {
        if (c.word(0) != "restore" && c.word(0) != "discard") fail("expects restore or discard");
        if (!m_recoveryOffered) fail("no recovery copy was offered at start");
        answerRecoveryOffer(c.word(0) == "restore");
    } else if (name == "wait-converged") {
        // Idle, and the last published pixels are on screen.
        // Every view: linked views render what the focused one's edits sent them.
        for (int i = 0; i < m_document->viewCount(); ++i)
            if (const RenderSession &session = m_document->view(i).renderSession();
                session.hasWork() || session.isRefinementHeld() || (m_views[std::size_t(i)].shown && !m_views[std::size_t(i)].current))
                return false;
    } else if (name == "wait-frames") {
        m_waitFrames = std::max(0, c.integer(0));
    } else if (name == "screenshot") {
        writeScreenshot(c.word(0));
    } else if (name == "window-screenshot") {
        m_pendingWindowShot = c.word(0);
        m_waitFrames = 1;
    } else if (name == "save-session") {
        m_controller->saveSession(c.word(0));
    } else if (name == "load-session") {
        stopHistogramWorker();
        m_controller->loadSession(c.word(0));
        refocus();
    } else if (name == "open") {
        // Several models: the layers of one scene. The script waits, frame after frame, until
        // the scene and its inferred layers are in: what follows acts on them.
        if (!m_scriptOpenStarted) {
            startOpening(c.args);
            m_scriptOpenStarted = true;
        }
        if (m_document->isLoading()) return false;
        m_scriptOpenStarted = false;
    } else if (name == "expect-lenses") {
        if (m_controller->lensCount() != c.integer(0))
            fail("the stack holds " + std::to_string(m_controller->lensCount()) + " lenses, not " + c.word(0));
    } else if (name == "bench-begin") {
        m_benchName = c.word(0);
        m_benchFrames.clear();
        m_benchImageUpdates = 0;
    } else if (name == "bench-end") {
        std::vector<double> frames = m_benchFrames;
        std::sort(frames.begin(), frames.end());
        if (!frames.empty()) {
            const size_t worstFrame = size_t(std::max_element(m_benchFrames.begin(), m_benchFrames.end()) - m_benchFrames.begin());
            std::printf("bench %s: %zu UI frames, median %.2f ms, 95th percentile %.2f ms, worst %.2f ms (frame %zu), "
                        "%llu image updates\n",
                        m_benchName.c_str(), frames.size(), frames[frames.size() / 2], frames[frames.size() * 95 / 100],
                        frames.back(), worstFrame + 1, (unsigned long long)m_benchImageUpdates);
        }
        std::fflush(stdout);
        m_benchName.clear();
    } else if (name == "add-keyframe") {
        addKeyframe(c.word(0), c.number(1));
    } else if (name == "write-turntable") {
        writeShortcutAnimation(c.word(0), c.integer(1), c.args.size() > 2 ? c.word(2) : std::string());
    } else if (name == "play") {
        // Starts once, then holds the script until the animation has played.
        if (m_playScriptLine != c.line) {
            m_playScriptLine = c.line;
            startPlaying(c.word(0));
        }
        if (m_player) return false;
    } else if (name == "record") {
        startRecording(c.word(0), c.number(1));
    } else if (name == "stop-recording") {
        stopRecording();
    } else if (name == "layout") {
        setLayout(parseViewLayout(c.word(0), "script line " + std::to_string(c.line)));
    } else if (name == "focus-view") {
        if (c.integer(0) >= m_document->viewCount())
            fail("no view " + c.word(0) + " (there are " + std::to_string(m_document->viewCount()) + "; a layout adds them)");
        m_document->setFocusedView(c.integer(0));
        refocus();
    } else if (name == "link" || name == "unlink") {
        const LinkAspect aspect = parseLinkAspect(c.word(0), "script line " + std::to_string(c.line));
        for (int i : {1, 2})
            if (c.integer(i) >= m_document->viewCount()) fail("no view " + c.word(i) + " (there are " + std::to_string(m_document->viewCount()) + ")");
        if (name == "link") m_document->link(c.integer(1), c.integer(2), aspect);
        else m_document->unlink(c.integer(1), c.integer(2), aspect);
    } else if (name == "compare") {
        m_controller->setCompareEnabled(c.word(0) == "on");
    } else if (name == "compare-divider") {
        if (!m_controller->isCompareEnabled()) fail("the focused view is not in compare mode (compare on)");
        m_controller->setCompareDivider(float(c.number(0)));
    } else if (runGizmoCommand(*m_controller, c, m_pointer)) { // gizmo-drag, fit-lens, follow-pointer
        m_waitFrames = 1;
    } else if (name == "quit") {
        m_exitCode = c.args.empty() ? 0 : c.integer(0);
        m_quit = true;
    }
    return true;
}

} // namespace mvcl::viewer
