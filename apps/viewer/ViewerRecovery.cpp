// The offer at start of the session the last run did not save: a modal with Restore and
// Discard (script: recovery restore|discard). Until it is answered the copy is left as it was:
// nothing is written to it, and quitting keeps it for the next start.

#include "Viewer.h"

#include <mvcl/core/Error.h>

#include <imgui.h>

namespace mvcl::viewer {

namespace {
constexpr const char *kRecoveryPopup = "Restore the unsaved session?";
}

void Viewer::offerRecovery() {
    if (!m_controller->hasRecovery()) return;
    m_recoveryOffered = true;
    const std::string copy = m_controller->recoveryPath().string();
    report("the last session was not saved; its recovery copy is " + copy +
           " (Restore or Discard in the window; a script answers with 'recovery restore|discard')");
}

void Viewer::answerRecoveryOffer(bool restore) {
    m_recoveryOffered = false;
    if (!restore) {
        m_controller->discardRecovery();
        report("the recovery copy is discarded");
        return;
    }
    stopHistogramWorker(); // the copy may name another scene
    m_controller->restoreRecovery(); // a broken copy throws: the caller reports it
    refocus(); // the copy may bring other views
    for (ViewDisplay &view : m_views) view.current = false;
    report("restored the unsaved session (" + std::to_string(m_controller->lensCount()) +
           " lenses); save it to keep it");
}

void Viewer::drawRecoveryOffer() {
    if (m_recoveryOffered && !ImGui::IsPopupOpen(kRecoveryPopup)) ImGui::OpenPopup(kRecoveryPopup);
    if (!ImGui::BeginPopupModal(kRecoveryPopup, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    if (!m_recoveryOffered) { // answered by a script
        ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
        return;
    }
    ImGui::TextUnformatted("The last session ended before it was saved.");
    ImGui::TextDisabled("%s", m_controller->recoveryPath().string().c_str());
    bool answered = false, restore = false;
    if (ImGui::Button("Restore")) answered = restore = true;
    ImGui::SameLine();
    if (ImGui::Button("Discard")) answered = true;
    if (answered) {
        ImGui::CloseCurrentPopup();
        try {
            answerRecoveryOffer(restore);
        } catch (const Error &e) {
            report(e.what());
        }
    }
    ImGui::EndPopup();
}

} // namespace mvcl::viewer
