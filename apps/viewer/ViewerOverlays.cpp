// What the viewer draws over the window: the rendered image, each lens's outline (the selected
// one brighter, with its handles), the help overlay and the message bar.

#include "Viewer.h"
#include "ViewerGizmos.h"

#include <mvcl/lens/LensStack.h>

#include <imgui.h>

#include <cmath>
#include <string>
#include <vector>

namespace mvcl::viewer {

namespace {

ImU32 colorOf(const glm::vec3 &linear, float alpha) {
    auto channel = [](float v) { return std::pow(std::clamp(v, 0.f, 1.f), 1.f / 2.2f); };
    return ImGui::GetColorU32(ImVec4(channel(linear.x), channel(linear.y), channel(linear.z), alpha));
}

/// Every binding, for the help overlay (F1); the controller's own are listed in Controller.h.
const char *const kBindings[][2] = {
    {"left drag on a 3D handle", "edit the selected lens's box, sphere, plane (Shift: along an axis)"},
    {"left drag on a lens", "move it (selects it)"},
    {"left drag on a handle", "resize the selected lens (corners, edges, polygon vertices)"},
    {"left drag elsewhere", "orbit about the target"},
    {"middle drag, Shift + left drag", "pan"},
    {"scroll", "zoom toward the point under the pointer"},
    {"F, Home", "frame everything"},
    {"1 ... 6", "front, back, left, right, top, bottom view"},
    {"keypad 1 / 3 / 7", "front / right / top (Ctrl: back / left / bottom)"},
    {"PageUp, PageDown", "raise, lower the selected lens"},
    {"Delete, Backspace", "delete the selected lens"},
    {"Ctrl+D", "duplicate the selected lens"},
    {"E", "enable or disable the selected lens"},
    {"B, Shift+B", "fit the selected lens's box to the object under the pointer / everything"},
    {"P", "pin the selected lens to the pointer, or unpin it"},
    {"Escape", "cancel the drag, else deselect"},
    {"Ctrl+Z / Ctrl+Shift+Z, Ctrl+Y", "undo / redo"},
    {"Ctrl+S", "save the session (session.json unless one is open)"},
    {"Ctrl+O", "open a model or a session file"},
    {"drop a .gltf/.glb or .json file", "open the model / the session"},
    {"F12", "screenshot of the rendered views (out/mvcl-viewer-N.png)"},
    {"F5 / F6 / F7 / F8", "layout: one view / 1x2 side by side / 2x1 stacked / 2x2"},
    {"Tab", "focus the next view (keys and panels act on the focused one)"},
    {"drag a compare divider", "move it (left of it stack A, right of it stack B)"},
    {"F1", "this help"},
    {"Ctrl+Q", "quit"},
};

} // namespace

void Viewer::drawImage() {
    ImDrawList *draw = ImGui::GetBackgroundDrawList();
    for (const ViewDisplay &view : m_views)
        if (view.shown && view.texture.width() > 0)
            draw->AddImage(ImTextureID(intptr_t(view.texture.glName())), ImVec2(view.screenOrigin.x, view.screenOrigin.y),
                           ImVec2(view.screenOrigin.x + view.screenSize.x, view.screenOrigin.y + view.screenSize.y));
}

void Viewer::drawLensOverlays() {
    for (int i = 0; i < m_document->viewCount(); ++i) {
        const ViewDisplay &view = m_views[std::size_t(i)];
        if (view.shown) drawViewOverlays(m_document->view(i), view.screenOrigin, view.screenSize);
    }
    drawViewFrames();
}

void Viewer::drawViewOverlays(const Controller &view, const glm::vec2 &origin, const glm::vec2 &size) {
    ImDrawList *draw = ImGui::GetBackgroundDrawList();
    const auto screenOf = [&](const glm::vec2 &normalized) { return origin + normalized * size; };
    const float thickness = 1.5f * m_contentScale;
    // One stack's outlines within [clipMin, clipMax); the stack being edited with labels, the
    // selected lens bright with its handles; the other side of a compare divider dimmed.
    const auto drawStack = [&](const LensStack &stack, bool edited, const glm::vec2 &clipMin, const glm::vec2 &clipMax) {
        draw->PushClipRect(ImVec2(clipMin.x, clipMin.y), ImVec2(clipMax.x, clipMax.y), true);
        for (int i = 0; i < stack.size(); ++i) {
            const Lens &lens = *stack.lens(i);
            const LensRegion &region = lens.region();
            const bool selected = edited && i == view.selectedLens();
            const ImU32 color = !edited          ? colorOf(glm::vec3(0.7f), 0.35f)
                                : lens.isEnabled() ? colorOf(selected ? glm::vec3(1.f, 0.85f, 0.2f) : glm::vec3(0.9f), selected ? 1.f : 0.6f)
                                                   : colorOf(glm::vec3(0.5f), 0.5f);
            const glm::vec2 c = screenOf(region.center());
            const glm::vec2 half = 0.5f * region.size() * size;
            switch (region.shape()) {
            case LensRegion::Shape::Rectangle:
                draw->AddRect(ImVec2(c.x - half.x, c.y - half.y), ImVec2(c.x + half.x, c.y + half.y), color, 0.f, 0, thickness);
                break;
            case LensRegion::Shape::Ellipse: {
                constexpr int kSegments = 96;
                ImVec2 points[kSegments];
                for (int k = 0; k < kSegments; ++k) {
                    const float a = 6.2831853f * float(k) / float(kSegments);
                    points[k] = ImVec2(c.x + half.x * std::cos(a), c.y + half.y * std::sin(a));
                }
                draw->AddPolyline(points, kSegments, color, ImDrawFlags_Closed, thickness);
                break;
            }
            case LensRegion::Shape::Polygon: {
                std::vector<ImVec2> points;
                for (const glm::vec2 &p : region.points()) {
                    const glm::vec2 s = screenOf(p);
                    points.emplace_back(s.x, s.y);
                }
                if (points.size() >= 2) draw->AddPolyline(points.data(), int(points.size()), color, ImDrawFlags_Closed, thickness);
                break;
            }
            }
            if (!edited) continue;
            const std::string label = lens.label().empty() ? lens.typeName() : lens.label();
            draw->AddText(ImVec2(c.x - half.x + 4.f, c.y - half.y + 2.f), color, label.c_str());
            if (!selected) continue;
            for (const LensHandle &handle : view.lensHandles(i)) {
                const glm::vec2 h = screenOf(handle.position);
                const float r = 4.f * m_contentScale;
                draw->AddRectFilled(ImVec2(h.x - r, h.y - r), ImVec2(h.x + r, h.y + r), color);
            }
        }
        draw->PopClipRect();
    };
    if (!view.isCompareEnabled()) {
        drawStack(view.lensStack(), true, origin, origin + size);
    } else {
        const float x = origin.x + view.compareDivider() * size.x;
        const bool leftEdited = view.compareSide() == CompareSide::Left;
        drawStack(view.leftLensStack(), leftEdited, origin, {x, origin.y + size.y});
        drawStack(view.rightLensStack(), !leftEdited, {x, origin.y}, origin + size);
        { // the divider, with a grip in the middle to show it can be dragged
            const ImU32 white = IM_COL32(255, 255, 255, 230);
            draw->AddLine(ImVec2(x, origin.y), ImVec2(x, origin.y + size.y), white, 2.f * m_contentScale);
            const float grip = 6.f * m_contentScale, middle = origin.y + 0.5f * size.y;
            draw->AddRectFilled(ImVec2(x - grip, middle - 3.f * grip), ImVec2(x + grip, middle + 3.f * grip), white, grip);
            draw->AddText(ImVec2(origin.x + 6.f, origin.y + size.y - ImGui::GetTextLineHeight() - 4.f), white, "A");
            draw->AddText(ImVec2(origin.x + size.x - 14.f * m_contentScale, origin.y + size.y - ImGui::GetTextLineHeight() - 4.f),
                          white, "B");
        }
    }
    // The selected lens's 3D handles, in this view only.
    draw->PushClipRect(ImVec2(origin.x, origin.y), ImVec2(origin.x + size.x, origin.y + size.y), true);
    drawGizmos(draw, view, origin, 1.f / m_framebufferScale, m_contentScale);
    draw->PopClipRect();
}

void Viewer::drawHelpOverlay() {
    if (!m_showHelp) return;
    ImGui::SetNextWindowPos(ImVec2(m_viewScreenSize.x * 0.5f, m_viewScreenSize.y * 0.5f), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.9f);
    if (ImGui::Begin("Help (F1)", &m_showHelp, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse)) {
        if (ImGui::BeginTable("bindings", 2, ImGuiTableFlags_RowBg)) {
            for (const auto &binding : kBindings) {
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(binding[0]);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(binding[1]);
            }
            ImGui::EndTable();
        }
        ImGui::TextDisabled("Panels on the right: lens stack, selected lens, layers, stats, what is under the pointer.");
    }
    ImGui::End();
}

void Viewer::drawMessages() {
    // The open in progress says what it does below the messages, while the old scene stays live.
    std::vector<std::string> lines(m_messages.begin(), m_messages.end());
    if (m_document && m_document->isLoading()) lines.push_back(m_document->loadProgress() + " ...");
    if (lines.empty()) return;
    const float lineHeight = ImGui::GetTextLineHeightWithSpacing();
    ImDrawList *draw = ImGui::GetForegroundDrawList();
    float y = m_viewScreenSize.y - lineHeight * float(lines.size()) - 6.f;
    for (const std::string &message : lines) {
        draw->AddRectFilled(ImVec2(4.f, y - 1.f), ImVec2(8.f + ImGui::CalcTextSize(message.c_str()).x, y + lineHeight - 2.f),
                            IM_COL32(0, 0, 0, 170));
        draw->AddText(ImVec2(6.f, y), IM_COL32(255, 230, 160, 255), message.c_str());
        y += lineHeight;
    }
}

} // namespace mvcl::viewer
