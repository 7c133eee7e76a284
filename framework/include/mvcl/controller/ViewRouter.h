#pragma once
/// \file ViewRouter.h
/// Which view of several an input event belongs to, as plain data (testable without a
/// window): the app gives the views' rectangles in window framebuffer pixels, route() answers
/// with the view and the event in that view's own pixels.
///
/// - A press goes to the view under the pointer and captures the pointer: moves and the
///   release go to that view until the release, even outside it. The pressed view gets the focus.
/// - Moves and scrolls without a press go to the view under the pointer (none outside every view).
/// - Keys and dropped files go to the focused view.
/// - Resize events go nowhere (the app resizes the views from their rectangles).

#include <mvcl/core/Export.h>

#include <mvcl/controller/InputEvent.h>

#include <glm/vec2.hpp>

#include <vector>

namespace mvcl {

/// Where a view is shown, in window framebuffer pixels.
struct ViewRect {
    int view = 0;
    glm::ivec2 origin{0};
    glm::ivec2 size{1};

    bool contains(const glm::vec2 &p) const {
        return p.x >= float(origin.x) && p.y >= float(origin.y) && p.x < float(origin.x + size.x) &&
               p.y < float(origin.y + size.y);
    }
    bool operator==(const ViewRect &other) const = default;
};

class MVCL_EXPORT ViewRouter {
public:
    struct Routed {
        int view = -1; ///< -1: no view
        InputEvent event; ///< positions in the view's framebuffer pixels
    };

    void setViewRects(std::vector<ViewRect> rects);
    const std::vector<ViewRect> &viewRects() const { return m_rects; }
    /// The rectangle of `view`, or nullptr when it is not shown.
    const ViewRect *rectOf(int view) const;
    /// The view under a window position, or -1.
    int viewAt(const glm::vec2 &position) const;

    int focus() const { return m_focus; }
    void setFocus(int view) { m_focus = view; }
    /// The view that has the pointer captured (a press not yet released), or -1.
    int capture() const { return m_capture; }

    /// Routes one event and updates focus and capture.
    Routed route(const InputEvent &event);

private:
    std::vector<ViewRect> m_rects;
    int m_focus = 0;
    int m_capture = -1;
    int m_pressedButtons = 0;
};

} // namespace mvcl
