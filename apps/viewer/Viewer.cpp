#include "Viewer.h"

#include <mvcl/core/Error.h>
#include <mvcl/view/ImageIO.h>
#include <mvcl/view/LensOutlines.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace mvcl::viewer {

namespace {

long long millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start).count();
}

/// The side panel's width in screen units, before the content scale.
constexpr float kPanelWidth = 380.f;
constexpr size_t kMessagesKept = 6;

std::vector<std::string> g_droppedPaths; // GLFW's drop callback has no user data of ours

RenderSettings interactiveSettings(const ViewerOptions &o) {
    RenderSettings s;
    s.threads = o.threads;
    s.sampling = o.sampling;
    s.samplesPerPixel = o.samplesPerPixel;
    s.minSamplesPerPixel = std::max(2, o.samplesPerPixel);
    s.maxSamplesPerPixel = std::max(o.maxSamplesPerPixel, s.minSamplesPerPixel);
    s.targetError = o.targetError;
    return s;
}

ViewRequest withDefaultScene(ViewRequest request) {
    if (request.source.empty() && request.sessionFile.empty()) request.source = "builtin:cube-in-cube";
    return request;
}

bool endsWith(const std::string &text, const std::string &suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

Viewer::Viewer(GLFWwindow *window, const ViewerOptions &options) : m_window(window), m_options(options) {
    for (const Error &skipped : m_registry.loadModules(LensRegistry::defaultSearchPath()))
        report("plugin skipped: " + std::string(skipped.what()));

    float scaleX = 1.f, scaleY = 1.f;
    glfwGetWindowContentScale(window, &scaleX, &scaleY);
    m_contentScale = std::max(scaleX, scaleY);
    if (m_contentScale != 1.f) {
        // Fonts drawn at the display's scale stay sharp; the style's sizes follow.
        ImFontConfig font;
        font.SizePixels = 13.f * m_contentScale;
        ImGui::GetIO().Fonts->AddFontDefault(&font);
        ImGui::GetStyle().ScaleAllSizes(m_contentScale);
    }

    m_script = options.script;

    layout();
    const glm::ivec2 viewSize = glm::max(glm::ivec2(m_viewScreenSize * m_framebufferScale), glm::ivec2(1));
    RenderSettings settings = interactiveSettings(options);
    settings.width = viewSize.x;
    settings.height = viewSize.y;
    const ViewRequest request = withDefaultScene(options.request);
    try {
        m_document = std::make_unique<Document>(m_registry, request, settings);
    } catch (const Error &e) {
        // The view opens on the default scene, so the user keeps a working window.
        report(std::string(e.what()) + " (showing builtin:cube-in-cube)");
        ViewRequest fallback;
        fallback.source = "builtin:cube-in-cube";
        m_document = std::make_unique<Document>(m_registry, fallback, settings);
    }
    m_document->setErrorCallback([this](const Error &e) { report(e.what()); });
    m_document->setViewsChangedCallback([this] {
        for (ViewDisplay &view : m_views) view.current = false;
    });
    refocus();
    if (!options.recovery.empty()) m_document->setRecoveryPath(options.recovery);
    offerRecovery(); // before any edit rewrites the copy
    layoutViews();
    m_document->startRendering();

    glfwSetDropCallback(window, [](GLFWwindow *, int count, const char **paths) {
        for (int i = 0; i < count; ++i) g_droppedPaths.emplace_back(paths[i]);
    });
}

Viewer::~Viewer() {
    // A clean exit: unsaved changes land in the recovery copy, else it goes; an offer not
    // answered keeps it for the next start.
    if (m_controller && !m_recoveryOffered) m_controller->finishRecovery();
    stopRecording();
    stopHistogramWorker();
    if (m_document) m_document->stopRendering();
    glfwSetDropCallback(m_window, nullptr);
}

void Viewer::report(const std::string &message) {
    std::fprintf(stderr, "mvcl-viewer: %s\n", message.c_str());
    m_messages.push_back(message);
    while (m_messages.size() > kMessagesKept) m_messages.pop_front();
}

void Viewer::layout() {
    int windowW = 0, windowH = 0, framebufferW = 0, framebufferH = 0;
    glfwGetWindowSize(m_window, &windowW, &windowH);
    glfwGetFramebufferSize(m_window, &framebufferW, &framebufferH);
    m_framebufferScale = {windowW > 0 ? float(framebufferW) / float(windowW) : 1.f,
                          windowH > 0 ? float(framebufferH) / float(windowH) : 1.f};
    m_panelWidth = std::min(kPanelWidth * m_contentScale, 0.5f * float(windowW));
    m_viewScreenSize = {std::max(float(windowW) - m_panelWidth, 1.f), std::max(float(windowH), 1.f)};
}

void Viewer::pollEvents() {
    const bool opening = m_document && m_document->isLoading() && (!m_openShowedScene || m_awaitingFirstImage);
    if (!opening) return glfwPollEvents();
    // Short waits, up to a tenth of a second in all, that end at once for input and for what the
    // load has to show: its next stage (a result is out) or the first pass of the new scene.
    constexpr std::chrono::milliseconds kOpeningFrame(100);
    constexpr std::chrono::duration<double> kSlice(0.005);
    const std::string progress = m_document->loadProgress();
    const RenderSession &session = m_document->view(m_document->focusedView()).renderSession();
    const uint64_t passes = session.passCount();
    while (Clock::now() - m_frameStart < kOpeningFrame) {
        const Clock::time_point before = Clock::now();
        glfwWaitEventsTimeout(kSlice.count());
        if (Clock::now() - before < kSlice * 0.8) return; // woken by an event
        if (session.passCount() != passes || m_document->loadProgress() != progress) return;
    }
}

void Viewer::update() {
    m_frameStart = Clock::now();
    if (!m_document) return;
    layout();
    layoutViews(); // the views are rendered in framebuffer pixels: sharp on high-DPI displays
    if (!g_droppedPaths.empty()) {
        InputEvent drop = InputEvent::fileDrop(m_pointer, g_droppedPaths);
        g_droppedPaths.clear();
        stopHistogramWorker(); // a dropped file may replace the scene
        m_openStart = Clock::now(); // dropped models open like startOpening()
        m_openShowedScene = false;
        handle(drop);
    }
    runScript();
    updateOpening();
    refocus();
    if (!m_recoveryOffered) m_controller->updateRecovery(); // the offered copy stays as it is until answered
    updatePlayback();
    takeImage();
    m_document->updateRenderPriority(); // the focused view refines first
    recordFrame();
}

void Viewer::takeImage() {
    for (int i = 0; i < m_document->viewCount(); ++i) {
        ViewDisplay &view = m_views[std::size_t(i)];
        PixelRect changed;
        RenderSession &session = m_document->view(i).renderSession();
        // Idle before the copy: then the copy holds the session's final pixels.
        const bool idle = !session.hasWork();
        // Never waits: when the session is publishing right now, the next frame takes it.
        if (!session.copyImage(view.image, changed)) continue;
        view.texture.update(view.image, changed);
        if (!changed.isEmpty()) ++m_benchImageUpdates;
        if (m_awaitingFirstImage && !changed.isEmpty()) {
            m_awaitingFirstImage = false;
            report("first image after " + std::to_string(millisecondsSince(m_openStart)) + " ms");
        }
        view.current = idle && view.image.width() > 0;
    }
}

void Viewer::handle(const InputEvent &event) {
    InputEvent inWindow = event;
    inWindow.position += glm::vec2(focusedDisplay().pixelOrigin);
    handleInWindow(inWindow);
}

void Viewer::handleInWindow(const InputEvent &event) {
    try {
        m_document->handle(event);
    } catch (const Error &e) {
        report(e.what());
    }
    refocus();
}

void Viewer::forwardInput() {
    ImGuiIO &io = ImGui::GetIO();
    KeyModifier modifiers = KeyModifier::None;
    if (io.KeyShift) modifiers = modifiers | KeyModifier::Shift;
    if (io.KeyCtrl) modifiers = modifiers | KeyModifier::Control;
    if (io.KeyAlt) modifiers = modifiers | KeyModifier::Alt;
    if (io.KeySuper) modifiers = modifiers | KeyModifier::Super;

    const glm::vec2 screen(io.MousePos.x, io.MousePos.y);
    const glm::vec2 pixel = screen * m_framebufferScale; // window framebuffer pixels
    const int viewUnder = ImGui::IsMousePosValid() ? m_document->router().viewAt(pixel) : -1;
    const bool overView = viewUnder >= 0 && !io.WantCaptureMouse;
    if (m_script) return; // a script drives the pointer and keys itself
    m_pointer = viewUnder >= 0 && viewUnder == m_document->focusedView() ? pixel - glm::vec2(focusedDisplay().pixelOrigin)
                                                                         : glm::vec2(-1.f);

    const bool dragging = m_document->router().capture() >= 0;
    if ((overView || dragging) && (io.MouseDelta.x != 0.f || io.MouseDelta.y != 0.f))
        handleInWindow(InputEvent::pointerMove(pixel, modifiers));
    const PointerButton buttons[] = {PointerButton::Left, PointerButton::Right, PointerButton::Middle};
    for (int b = 0; b < 3; ++b) {
        if (ImGui::IsMouseClicked(b) && overView) handleInWindow(InputEvent::pointerPress(pixel, buttons[b], modifiers));
        if (ImGui::IsMouseReleased(b) && (overView || dragging))
            handleInWindow(InputEvent::pointerRelease(pixel, buttons[b], modifiers));
    }
    if (overView && io.MouseWheel != 0.f) handleInWindow(InputEvent::scrolled(pixel, {0.f, io.MouseWheel}, modifiers));

    if (io.WantCaptureKeyboard) return;
    static const std::pair<int, Key> kKeys[] = {
        {GLFW_KEY_1, Key::Digit1}, {GLFW_KEY_2, Key::Digit2}, {GLFW_KEY_3, Key::Digit3},
        {GLFW_KEY_4, Key::Digit4}, {GLFW_KEY_5, Key::Digit5}, {GLFW_KEY_6, Key::Digit6},
        {GLFW_KEY_KP_1, Key::Keypad1}, {GLFW_KEY_KP_3, Key::Keypad3}, {GLFW_KEY_KP_7, Key::Keypad7},
        {GLFW_KEY_B, Key::B}, {GLFW_KEY_P, Key::P}, {GLFW_KEY_D, Key::D}, {GLFW_KEY_E, Key::E}, {GLFW_KEY_F, Key::F}, {GLFW_KEY_Y, Key::Y},
        {GLFW_KEY_Z, Key::Z}, {GLFW_KEY_HOME, Key::Home}, {GLFW_KEY_PAGE_UP, Key::PageUp},
        {GLFW_KEY_PAGE_DOWN, Key::PageDown}, {GLFW_KEY_DELETE, Key::Delete},
        {GLFW_KEY_BACKSPACE, Key::Backspace}, {GLFW_KEY_ESCAPE, Key::Escape},
    };
    for (const auto &[glfwKey, key] : kKeys)
        if (ImGui::IsKeyPressed(glfwKey)) handle(InputEvent::keyPress(key, modifiers));
    handleViewerKeys();
}

void Viewer::handleViewerKeys() {
    const ImGuiIO &io = ImGui::GetIO();
    if (ImGui::IsKeyPressed(GLFW_KEY_F1, false)) m_showHelp = !m_showHelp;
    if (ImGui::IsKeyPressed(GLFW_KEY_F12, false))
        writeScreenshot("out/mvcl-viewer-" + std::to_string(++m_screenshotCount) + ".png");
    if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_S, false)) {
        const std::filesystem::path session = m_controller->sessionPath();
        saveSession(session.empty() ? "session.json" : session.string());
    }
    if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_O, false)) m_openPopupRequested = true;
    if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Q, false)) m_quit = true;
    // Layouts: F5 one view, F6 two side by side, F7 two stacked, F8 four; Tab: the next view.
    const std::pair<int, ViewLayout> kLayoutKeys[] = {{GLFW_KEY_F5, ViewLayout::Single}, {GLFW_KEY_F6, ViewLayout::Columns},
                                                      {GLFW_KEY_F7, ViewLayout::Rows}, {GLFW_KEY_F8, ViewLayout::Grid}};
    for (const auto &[glfwKey, layout] : kLayoutKeys)
        if (ImGui::IsKeyPressed(glfwKey, false)) setLayout(layout);
    if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false)) {
        const std::vector<int> shown = m_document->shownViews();
        const auto at = std::find(shown.begin(), shown.end(), m_document->focusedView());
        const int next = shown.size() > 1 && at != shown.end() ? shown[std::size_t((at - shown.begin() + 1)) % shown.size()]
                                                               : (m_document->focusedView() + 1) % m_document->viewCount();
        m_document->setFocusedView(next);
        refocus();
    }
}

void Viewer::writeScreenshot(const std::string &file) {
    // Every shown view as the sessions have it, with the lenses' outline joins, no UI.
    const Framebuffer image = composedViews();
    try {
        std::filesystem::create_directories(std::filesystem::path(file).parent_path().empty()
                                                ? std::filesystem::path(".")
                                                : std::filesystem::path(file).parent_path());
        writeImage(file, image);
        report("wrote " + file);
    } catch (const std::exception &e) {
        report(e.what());
    }
}

void Viewer::saveSession(const std::string &file) {
    try {
        m_controller->saveSession(file);
        report("saved " + file);
    } catch (const Error &e) {
        report(e.what());
    }
}

void Viewer::openFile(const std::string &file) {
    // A lens-stack file is a session; anything else is a model. Errors leave the view as it was.
    if (!endsWith(file, ".json")) return startOpening({file});
    stopHistogramWorker();
    try {
        m_controller->loadSession(file);
        report("opened " + file);
    } catch (const Error &e) {
        report(e.what());
    }
    refocus(); // a session may bring other views
}

void Viewer::startOpening(const std::vector<std::string> &files) {
    m_openStart = Clock::now();
    m_openShowedScene = false;
    m_document->openScenes(files);
}

void Viewer::updateOpening() {
    if (!m_document->isLoading()) return;
    stopHistogramWorker(); // the tracer it reads is about to be replaced
    if (!m_document->updateSceneLoad()) return;
    const std::string after = " after " + std::to_string(millisecondsSince(m_openStart)) + " ms";
    const Scene &scene = m_document->scene();
    const TracerBuildStats &bvh = m_document->tracer().buildStats();
    const bool quickBvh = bvh.bvhQuality == BvhQuality::Quick;
    if (!m_openShowedScene) {
        const std::string next = m_document->isLoading() ? quickBvh ? "; a quick BVH until the full one is built"
                                                                    : "; inferring its layers"
                                                         : "";
        report("showing " + scene.name + after + " (" + (quickBvh ? "quick " : "") + "BVH " +
               std::to_string(std::lround(bvh.buildMilliseconds)) + " ms)" + next);
        m_awaitingFirstImage = true;
        m_openShowedScene = true;
    } else if (&scene == m_openShownScene) { // the same scene on its full BVH
        report("full BVH of " + scene.name + " built" + after + " (" + std::to_string(std::lround(bvh.buildMilliseconds)) +
               " ms)");
    } else {
        report("layers of " + scene.name + " inferred" + after);
    }
    m_openShownScene = &scene;
    refocus();
}

void Viewer::frameDrawn() {
    if (!m_pendingWindowShot.empty()) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(m_window, &w, &h);
        std::vector<uint8_t> rgb(size_t(w) * size_t(h) * 3);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
        Framebuffer shot(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const uint8_t *p = &rgb[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 3];
                shot.at(x, y) = {srgbToLinear(p[0] / 255.f), srgbToLinear(p[1] / 255.f), srgbToLinear(p[2] / 255.f)};
            }
        try {
            writeImage(m_pendingWindowShot, shot);
            report("wrote " + m_pendingWindowShot);
        } catch (const std::exception &e) {
            report(e.what());
        }
        m_pendingWindowShot.clear();
    }
    m_lastFrameMs = std::chrono::duration<double, std::milli>(Clock::now() - m_frameStart).count();
    m_frameTimes.push_back(m_lastFrameMs);
    while (m_frameTimes.size() > 120) m_frameTimes.pop_front();
    if (!m_benchName.empty()) m_benchFrames.push_back(m_lastFrameMs);
}

} // namespace mvcl::viewer
