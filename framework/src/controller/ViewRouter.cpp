#include <mvcl/controller/ViewRouter.h>

namespace mvcl {

void ViewRouter::setViewRects(std::vector<ViewRect> rects) {
    m_rects = std::move(rects);
    if (m_capture >= 0 && !rectOf(m_capture)) { // the captured view went away
        m_capture = -1;
        m_pressedButtons = 0;
    }
}

const ViewRect *ViewRouter::rectOf(int view) const {
    for (const ViewRect &rect : m_rects)
        if (rect.view == view) return &rect;
    return nullptr;
}

int ViewRouter::viewAt(const glm::vec2 &position) const {
    for (const ViewRect &rect : m_rects)
        if (rect.contains(position)) return rect.view;
    return -1;
}

ViewRouter::Routed ViewRouter::route(const InputEvent &event) {
    Routed routed;
    routed.event = event;
    const auto toView = [&](int view) {
        routed.view = view;
        if (const ViewRect *rect = rectOf(view)) routed.event.position = event.position - glm::vec2(rect->origin);
    };
    switch (event.type) {
    case InputEvent::Type::PointerPress:
        if (m_capture < 0) {
            const int view = viewAt(event.position);
            if (view < 0) return routed;
            m_capture = view;
            m_focus = view;
        }
        ++m_pressedButtons;
        toView(m_capture);
        break;
    case InputEvent::Type::PointerRelease:
        if (m_capture < 0) return routed;
        toView(m_capture);
        if (--m_pressedButtons <= 0) {
            m_pressedButtons = 0;
            m_capture = -1;
        }
        break;
    case InputEvent::Type::PointerMove:
        toView(m_capture >= 0 ? m_capture : viewAt(event.position));
        break;
    case InputEvent::Type::Scroll: toView(viewAt(event.position)); break;
    case InputEvent::Type::KeyPress:
    case InputEvent::Type::FileDrop: routed.view = m_focus; break;
    case InputEvent::Type::Resize: break;
    }
    if (routed.view >= 0 && event.type != InputEvent::Type::KeyPress && event.type != InputEvent::Type::FileDrop &&
        !rectOf(routed.view))
        routed.view = -1;
    return routed;
}

} // namespace mvcl
