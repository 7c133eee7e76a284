// Several views in one window: the layout's grid in the image area, the frame around the
// focused view and the screenshot of every view as laid out. (The Views panel is with the other
// panels, ViewerPanels.cpp.)

#include "Viewer.h"

#include <mvcl/view/LensOutlines.h>
#include <mvcl/view/RenderSession.h>

#include <imgui.h>

#include <algorithm>
#include <string>

namespace mvcl::viewer {

void Viewer::layoutViews() {
    const std::vector<int> shown = m_document->shownViews();
    const ViewGrid grid = m_document->layout() == ViewLayout::Single ? ViewGrid{1, 1} : viewGridOf(m_document->layout());
    const glm::vec2 cell = m_viewScreenSize / glm::vec2(float(grid.columns), float(grid.rows));
    std::vector<ViewRect> rects;
    for (ViewDisplay &view : m_views) view.shown = false;
    for (std::size_t k = 0; k < shown.size(); ++k) {
        ViewDisplay &view = m_views[std::size_t(shown[k])];
        const glm::vec2 cellIndex(float(int(k) % grid.columns), float(int(k) / grid.columns));
        view.shown = true;
        view.screenOrigin = cellIndex * cell;
        view.screenSize = cell;
        // Whole framebuffer pixels; the last column and row take what rounding leaves.
        const glm::ivec2 from(glm::floor(view.screenOrigin * m_framebufferScale));
        const glm::ivec2 to(glm::floor((view.screenOrigin + cell) * m_framebufferScale));
        view.pixelOrigin = from;
        rects.push_back({shown[k], from, glm::max(to - from, glm::ivec2(1))});
    }
    bool resized = rects != m_document->router().viewRects();
    for (const ViewRect &rect : rects)
        resized = resized || m_document->view(rect.view).contentScale() != m_contentScale;
    if (resized) m_document->setViewRects(rects, m_contentScale);
}

void Viewer::refocus() {
    Controller *focused = &m_document->focused();
    if (focused == m_controller) return;
    // The panels' open edit step and the pick cache belong to the view that had the focus.
    if (m_editStepOpen) {
        m_document->endEditStep();
        m_editStepOpen = false;
    }
    stopHistogramWorker();
    m_pickMap.reset();
    m_pickSnapshots.clear();
    m_controller = focused;
    m_pointer = glm::vec2(-1.f);
}

void Viewer::setLayout(ViewLayout layout) {
    try {
        m_document->setLayout(layout);
    } catch (const Error &e) {
        report(e.what());
    }
    layoutViews();
    refocus();
}

Framebuffer Viewer::composedViews() const {
    const std::vector<ViewRect> &rects = m_document->router().viewRects();
    if (rects.empty()) return {};
    glm::ivec2 extent(0);
    for (const ViewRect &rect : rects) extent = glm::max(extent, rect.origin + rect.size);
    Framebuffer composed(extent.x, extent.y);
    for (const ViewRect &rect : rects) {
        const Controller &view = m_document->view(rect.view);
        Framebuffer image = m_views[std::size_t(rect.view)].image;
        if (image.width() == 0) continue;
        if (view.isCompareEnabled()) drawLensOutlines(view.leftLensStack(), view.rightLensStack(), view.compareDivider(), image);
        else drawLensOutlines(view.lensStack(), image);
        for (int y = 0; y < std::min(image.height(), rect.size.y); ++y)
            for (int x = 0; x < std::min(image.width(), rect.size.x); ++x)
                composed.at(rect.origin.x + x, rect.origin.y + y) = image.at(x, y);
    }
    return composed;
}

void Viewer::drawViewFrames() {
    const std::vector<int> shown = m_document->shownViews();
    if (shown.size() < 2) return;
    ImDrawList *draw = ImGui::GetBackgroundDrawList();
    for (int index : shown) {
        const ViewDisplay &view = m_views[std::size_t(index)];
        const bool focused = index == m_document->focusedView();
        const float inset = focused ? 1.f * m_contentScale : 0.5f;
        draw->AddRect(ImVec2(view.screenOrigin.x + inset, view.screenOrigin.y + inset),
                      ImVec2(view.screenOrigin.x + view.screenSize.x - inset, view.screenOrigin.y + view.screenSize.y - inset),
                      focused ? IM_COL32(255, 200, 60, 255) : IM_COL32(60, 60, 66, 255), 0.f, 0,
                      focused ? 2.f * m_contentScale : 1.f);
        const std::string name = "view " + std::to_string(index);
        draw->AddText(ImVec2(view.screenOrigin.x + 6.f, view.screenOrigin.y + 4.f),
                      focused ? IM_COL32(255, 200, 60, 255) : IM_COL32(200, 200, 200, 200), name.c_str());
    }
}

} // namespace mvcl::viewer
