// The viewer's animation panel: keyframes of the view into an animation file, playback of the
// file on the view, and recording of what the view shows. The framework does the work
// (ViewKeyframes, AnimationPlayer, ViewRecorder); this file wires it to the panel and the clock.

#include "Viewer.h"

#include <mvcl/controller/ViewKeyframes.h>
#include <mvcl/core/Error.h>
#include <mvcl/io/AnimationFile.h>
#include <mvcl/view/LensOutlines.h>
#include <mvcl/view/RenderSession.h>

#include <imgui.h>

#include <algorithm>
#include <filesystem>

namespace mvcl::viewer {

namespace {

/// ImGui's text field over a std::string (imgui 1.86 has no std::string overload).
bool inputText(const char *label, std::string &text) {
    char buffer[512];
    const std::size_t length = std::min(text.size(), sizeof buffer - 1);
    std::copy_n(text.begin(), length, buffer);
    buffer[length] = '\0';
    if (!ImGui::InputText(label, buffer, sizeof buffer)) return false;
    text = buffer;
    return true;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

void Viewer::drawAnimationPanel() {
    const auto attempt = [this](auto &&action) {
        try {
            action();
        } catch (const Error &e) {
            report(e.what());
        }
    };
    inputText("file", m_animationFile);
    ImGui::DragFloat("time (s)", &m_keyframeSeconds, 0.05f, 0.f, 3600.f, "%.2f");
    if (ImGui::Button("Add keyframe")) attempt([&] { addKeyframe(m_animationFile, m_keyframeSeconds); });
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the camera and the selected lens's properties and region");
    ImGui::SameLine();
    if (!m_player) {
        if (ImGui::Button("Play")) attempt([&] { startPlaying(m_animationFile); });
    } else {
        ImGui::Text("%.2f / %.2f s", secondsSince(m_playStart), m_player->animation().duration());
        ImGui::SameLine();
        if (ImGui::Button("Stop")) stopPlaying();
    }
    // The command line's shortcuts, written into the file for Play and Record.
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.35f);
    ImGui::InputInt("turntable frames", &m_turntableFrames);
    m_turntableFrames = std::clamp(m_turntableFrames, 0, 1 << 20);
    inputText("sweep", m_sweepSpec);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("LENS.PROPERTY=FROM:TO, e.g. reveal.distance=0:4 (a label or an index)");
    if (ImGui::Button("Write turntable / sweep"))
        attempt([&] { writeShortcutAnimation(m_animationFile, m_turntableFrames, m_sweepSpec); });
    ImGui::Separator();
    inputText("record to", m_recordTarget);
    ImGui::DragFloat("frames/s", &m_recordFrameRate, 1.f, 1.f, 120.f, "%.0f");
    if (!m_recorder) {
        if (ImGui::Button("Record")) attempt([&] { startRecording(m_recordTarget, m_recordFrameRate); });
    } else {
        ImGui::Text("%d frames", m_recorder->framesWritten());
        ImGui::SameLine();
        if (ImGui::Button("Stop recording")) stopRecording();
    }
}

void Viewer::addKeyframe(const std::string &file, double seconds) {
    const LensStack &lenses = m_controller->lensStack();
    Animation animation;
    if (std::filesystem::exists(file)) animation = readAnimationFile(file, lenses);
    else animation.setDuration(std::max(seconds, 1.0));
    animation.setDuration(std::max(animation.duration(), seconds));
    animation.addCameraKeyframe(cameraKeyframeOf(m_controller->camera(), m_controller->coordinates(), seconds));
    const int selected = m_controller->selectedLens();
    if (selected >= 0) animation.addLensKeyframe(selected, lensKeyframeOf(*lenses.lens(selected), seconds));
    writeAnimationFile(file, animation, lenses);
    report("keyframe at " + std::to_string(seconds) + " s added to " + file +
           (selected >= 0 ? " (camera and lens " + std::to_string(selected) + ")" : " (camera; select a lens to key it)"));
}

void Viewer::writeShortcutAnimation(const std::string &file, int turntableFrames, const std::string &sweepSpec) {
    const LensStack &lenses = m_controller->lensStack();
    constexpr double kFrameRate = 30.0;
    Animation animation;
    if (turntableFrames > 0) {
        animation = Animation::turntable(turntableFrames, kFrameRate);
    } else {
        if (sweepSpec.empty()) throw Error("animation", "give a number of turntable frames, a sweep, or both");
        animation.setFrameRate(kFrameRate);
        animation.setDuration(1.0);
    }
    if (!sweepSpec.empty()) addSweepSpec(animation, sweepSpec, lenses);
    writeAnimationFile(file, animation, lenses);
    report("wrote " + file + ": " + std::to_string(animation.frameCount()) + " frames; Play or Record it");
}

void Viewer::startPlaying(const std::string &file) {
    stopPlaying();
    m_player.emplace(readAnimationFile(file, m_controller->lensStack()), m_controller->lensStack(),
                     m_controller->camera(), m_controller->coordinates());
    m_playStart = Clock::now();
}

void Viewer::updatePlayback() {
    if (!m_player) return;
    const double seconds = secondsSince(m_playStart);
    if (seconds > m_player->animation().duration()) {
        stopPlaying();
        return;
    }
    // A preview, not an edit: the render session shows it, the controller's state stays.
    RenderSession &session = m_controller->renderSession();
    session.setCamera(m_player->showTime(seconds));
    session.setLensStack(m_controller->lensStack());
}

void Viewer::stopPlaying() {
    if (!m_player) return;
    m_player->restoreLenses();
    m_player.reset();
    RenderSession &session = m_controller->renderSession();
    session.setCamera(m_controller->camera());
    session.setLensStack(m_controller->lensStack());
}

void Viewer::startRecording(const std::string &target, double frameRate) {
    stopRecording();
    m_recorder.emplace(target, m_controller->viewSize(), frameRate);
    m_recordStart = Clock::now();
    report("recording to " + target);
}

void Viewer::recordFrame() {
    if (!m_recorder || focusedDisplay().image.width() == 0) return;
    // What the view shows, as a screenshot has it: the image with lens outlines, no panels.
    Framebuffer image = focusedDisplay().image;
    drawLensOutlines(m_controller->lensStack(), image);
    try {
        m_recorder->addImage(secondsSince(m_recordStart), image);
    } catch (const Error &e) {
        report(e.what());
        stopRecording();
    }
}

void Viewer::stopRecording() {
    if (!m_recorder) return;
    const int frames = m_recorder->framesWritten();
    try {
        m_recorder->finish();
        report("recorded " + std::to_string(frames) + " frames");
    } catch (const Error &e) {
        report(e.what());
    }
    m_recorder.reset();
}

} // namespace mvcl::viewer
