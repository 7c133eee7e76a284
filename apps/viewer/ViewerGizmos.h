#pragma once
// The viewer's side of the 3D lens handles: drawing the lines and dots the controller gives
// (no 3D maths here) and the script commands that drive them.

#include "ViewerScript.h"

#include <glm/vec2.hpp>

struct ImDrawList;

namespace mvcl {
class Controller;
}

namespace mvcl::viewer {

/// Draws controller.gizmoDrawing() with framebuffer pixel p at origin + p · screenPerPixel
/// (ImGui screen units); `contentScale` widens lines and dots on high-DPI displays.
void drawGizmos(ImDrawList *draw, const Controller &controller, const glm::vec2 &origin,
                const glm::vec2 &screenPerPixel, float contentScale);

/// Runs gizmo-drag, fit-lens and follow-pointer; false for any other command. `pointer` is the
/// script's pointer (framebuffer pixels), the place `fit-lens INDEX object` looks at. Throws
/// mvcl::Error naming the script line for bad arguments.
bool runGizmoCommand(Controller &controller, const ScriptCommand &command, const glm::vec2 &pointer);

} // namespace mvcl::viewer
