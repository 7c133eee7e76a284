// Drawing the 3D lens handles and the script commands that drive them (ViewerGizmos.h).

#include "ViewerGizmos.h"

#include <mvcl/controller/Controller.h>
#include <mvcl/core/Error.h>

#include <imgui.h>

#include <string>

namespace mvcl::viewer {

namespace {

ImU32 gizmoColor(int axis, GizmoDrawing::State state) {
    // x red, y green, z blue, the rest white; hovered and dragged parts turn yellow.
    if (state != GizmoDrawing::State::Normal) return IM_COL32(255, 220, 60, 255);
    switch (axis) {
    case 0: return IM_COL32(235, 80, 80, 230);
    case 1: return IM_COL32(90, 215, 90, 230);
    case 2: return IM_COL32(90, 140, 255, 230);
    default: return IM_COL32(240, 240, 240, 220);
    }
}

} // namespace

void drawGizmos(ImDrawList *draw, const Controller &controller, const glm::vec2 &origin,
                const glm::vec2 &screenPerPixel, float contentScale) {
    const GizmoDrawing drawing = controller.gizmoDrawing();
    const auto screen = [&](const glm::vec2 &pixel) {
        const glm::vec2 p = origin + pixel * screenPerPixel;
        return ImVec2(p.x, p.y);
    };
    for (const GizmoDrawing::Line &line : drawing.lines) {
        const float thickness = (line.state == GizmoDrawing::State::Normal ? 1.5f : 2.5f) * contentScale;
        for (const auto &segment : line.segments)
            draw->AddLine(screen(segment[0]), screen(segment[1]), gizmoColor(line.axis, line.state), thickness);
    }
    for (const GizmoDrawing::Dot &dot : drawing.dots) {
        const float radius = (dot.state == GizmoDrawing::State::Normal ? 5.f : 7.f) * contentScale;
        draw->AddCircleFilled(screen(dot.position), radius, gizmoColor(dot.axis, dot.state));
        draw->AddCircle(screen(dot.position), radius, IM_COL32(0, 0, 0, 200), 0, 1.f * contentScale);
    }
}

bool runGizmoCommand(Controller &controller, const ScriptCommand &c, const glm::vec2 &pointer) {
    const auto fail = [&](const std::string &problem) {
        throw Error("script line " + std::to_string(c.line), c.name + ": " + problem);
    };
    try {
        if (c.name == "gizmo-drag") {
            controller.dragGizmoHandle(c.integer(0), c.word(1), {float(c.number(2)), float(c.number(3))}, c.modifiers());
        } else if (c.name == "fit-lens") {
            const std::string &what = c.word(1);
            if (what == "object") controller.fitLens(c.integer(0), LensFit::Object, 0, pointer);
            else if (what == "all") controller.fitLens(c.integer(0), LensFit::All);
            else if (what == "layer" && c.args.size() == 3) controller.fitLens(c.integer(0), LensFit::Layer, c.integer(2));
            else fail("expects object, all or layer N");
        } else if (c.name == "follow-pointer") {
            if (c.word(1) != "on" && c.word(1) != "off") fail("expects on or off");
            controller.setPointerFollowingLens(c.word(1) == "on" ? c.integer(0) : -1);
        } else {
            return false;
        }
    } catch (const Error &e) {
        if (e.source().starts_with("script line")) throw;
        fail(e.what());
    }
    return true;
}

} // namespace mvcl::viewer
