// Controller: input events → edits (the key bindings are listed in Controller.h).

#include "Controller_p.h"

#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace mvcl {

namespace {

/// Orbit speed: half a turn for a drag across the view's height.
constexpr float kOrbitRadiansPerViewHeight = glm::pi<float>();
/// Zoom per scroll-wheel step: 15 % nearer.
constexpr float kZoomPerScrollStep = 0.85f;
/// No side of a resized region gets nearer its opposite than this (framebuffer pixels).
constexpr float kMinimumRegionPixels = 2.f;

bool isSessionFile(const std::string &path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".json";
}

} // namespace

bool Controller::handle(const InputEvent &event) {
    try {
        switch (event.type) {
        case InputEvent::Type::PointerPress: return d->pointerPress(event);
        case InputEvent::Type::PointerMove: return d->pointerMove(event);
        case InputEvent::Type::PointerRelease: return d->pointerRelease(event);
        case InputEvent::Type::Scroll: return d->scroll(event);
        case InputEvent::Type::KeyPress: return d->keyPress(event);
        case InputEvent::Type::FileDrop: return d->fileDrop(event);
        case InputEvent::Type::Resize:
            resizeView(event.framebufferSize, event.contentScale);
            return true;
        }
    } catch (const Error &e) {
        d->report(e);
    }
    return false;
}

bool Controller::isDragging() const { return d->drag.kind != DragKind::None; }
DragKind Controller::dragKind() const { return d->drag.kind; }

// --- pointer ---------------------------------------------------------------------------------------

bool Controller::Private::pointerPress(const InputEvent &event) {
    if (drag.kind != DragKind::None) return false; // another button while dragging
    if (event.button == PointerButton::Left) {
        // A 3D handle wins over lenses, Shift-pan and orbit.
        if (const std::optional<GizmoHandle> handle = gizmoAt(event.position)) {
            startGizmoDrag(selected, *handle, event.position, event.button);
            return true;
        }
    }
    Drag started;
    started.button = event.button;
    started.pressPosition = event.position;
    if (event.button == PointerButton::Middle ||
        (event.button == PointerButton::Left && hasModifier(event.modifiers, KeyModifier::Shift))) {
        started.kind = DragKind::Pan;
    } else if (event.button == PointerButton::Left) {
        const LensHit hit = q.hitTest(event.position);
        switch (hit.target) {
        case LensHit::Target::Handle: started.kind = DragKind::ResizeLens; break;
        case LensHit::Target::Lens: started.kind = DragKind::MoveLens; break;
        case LensHit::Target::Nothing:
        case LensHit::Target::Gizmo: started.kind = DragKind::Orbit; break; // handles were tried above
        }
        started.lens = hit.lens;
        started.handle = hit.handle;
        if (hit.lens >= 0) {
            selected = hit.lens; // grabbing a lens selects it, and undoing the drag keeps it selected
            started.startRegion = stack.lens(hit.lens)->snapshot()->region;
        }
    } else {
        return false;
    }
    started.startCamera = camera;
    started.start = captureStep();
    drag = started;
    q.beginEditStep(); // press to release is one step
    return true;
}

bool Controller::Private::pointerMove(const InputEvent &event) {
    if (drag.kind == DragKind::None) return hover(event.position);
    const glm::vec2 offset = event.position - drag.pressPosition;
    drag.hasMoved = drag.hasMoved || offset != glm::vec2(0.f);
    const ViewCoordinates view = coordinates();
    switch (drag.kind) {
    case DragKind::MoveLens:
        commitRegion(drag.lens, translatedRegion(drag.startRegion, view.normalizedFromPixelOffset(offset)));
        break;
    case DragKind::ResizeLens:
        commitRegion(drag.lens, drag.handle.moved(drag.startRegion, view.normalizedFromPixelOffset(offset),
                                                  view.normalizedFromPixelOffset(glm::vec2(kMinimumRegionPixels))));
        break;
    case DragKind::Orbit: {
        const float radiansPerPixel = kOrbitRadiansPerViewHeight / float(viewSize.y);
        // Dragging right turns the scene right (the eye goes left); dragging down raises the eye.
        camera = orbitCamera(drag.startCamera, -offset.x * radiansPerPixel, offset.y * radiansPerPixel);
        sendCamera();
        break;
    }
    case DragKind::Pan:
        camera = panCamera(drag.startCamera, offset, viewSize);
        sendCamera();
        break;
    case DragKind::Gizmo: moveGizmo(event.position, event.modifiers); break;
    case DragKind::None: break;
    }
    return true;
}

bool Controller::Private::pointerRelease(const InputEvent &event) {
    if (drag.kind == DragKind::None || event.button != drag.button) return false;
    if (drag.kind == DragKind::Orbit && !drag.hasMoved) selected = -1; // a click on the empty image
    drag = {};
    q.endEditStep();
    return true;
}

void Controller::Private::cancelDrag() {
    if (drag.kind == DragKind::None) return;
    restore(drag.start);
    drag = {};
    q.endEditStep(); // nothing changed since the press, so no step
}

bool Controller::Private::scroll(const InputEvent &event) {
    if (drag.kind != DragKind::None || event.scroll.y == 0.f) return false;
    q.zoomAt(event.position, std::pow(kZoomPerScrollStep, event.scroll.y));
    return true;
}

// --- keys --------------------------------------------------------------------------------------------

bool Controller::Private::keyPress(const InputEvent &event) {
    if (drag.kind != DragKind::None) {
        if (event.key != Key::Escape) return false; // a drag stays one step
        cancelDrag();
        return true;
    }
    const bool control = hasModifier(event.modifiers, KeyModifier::Control);
    const bool shift = hasModifier(event.modifiers, KeyModifier::Shift);
    const bool hasSelection = selected >= 0 && selected < stack.size();
    switch (event.key) {
    case Key::Z:
        if (!control) return false;
        shift ? q.redo() : q.undo();
        return true;
    case Key::Y:
        if (!control) return false;
        q.redo();
        return true;
    case Key::F:
    case Key::Home: q.frameAll(); return true;
    case Key::Digit1: q.setViewPreset(ViewPreset::Front); return true;
    case Key::Digit2: q.setViewPreset(ViewPreset::Back); return true;
    case Key::Digit3: q.setViewPreset(ViewPreset::Left); return true;
    case Key::Digit4: q.setViewPreset(ViewPreset::Right); return true;
    case Key::Digit5: q.setViewPreset(ViewPreset::Top); return true;
    case Key::Digit6: q.setViewPreset(ViewPreset::Bottom); return true;
    case Key::Keypad1: q.setViewPreset(control ? ViewPreset::Back : ViewPreset::Front); return true;
    case Key::Keypad3: q.setViewPreset(control ? ViewPreset::Left : ViewPreset::Right); return true;
    case Key::Keypad7: q.setViewPreset(control ? ViewPreset::Bottom : ViewPreset::Top); return true;
    case Key::PageUp:
        if (!hasSelection) return false;
        q.raiseLens(selected);
        return true;
    case Key::PageDown:
        if (!hasSelection) return false;
        q.lowerLens(selected);
        return true;
    case Key::Delete:
    case Key::Backspace:
        if (!hasSelection) return false;
        q.removeLens(selected);
        return true;
    case Key::D:
        if (!control || !hasSelection) return false;
        q.duplicateLens(selected);
        return true;
    case Key::E:
        if (!hasSelection) return false;
        q.setLensEnabled(selected, !stack.lens(selected)->snapshot()->enabled);
        return true;
    case Key::B:
        if (!hasSelection) return false;
        q.fitLens(selected, shift ? LensFit::All : LensFit::Object, 0, pointer);
        return true;
    case Key::P:
        if (!hasSelection) return false;
        q.setPointerFollowingLens(followerIndex() == selected ? -1 : selected);
        return true;
    case Key::Escape:
        if (selected < 0) return false;
        selected = -1;
        return true;
    case Key::Other: return false;
    }
    return false;
}

// --- files -----------------------------------------------------------------------------------------------

bool Controller::Private::fileDrop(const InputEvent &event) {
    if (event.paths.empty()) return false;
    const auto session = std::ranges::find_if(event.paths, isSessionFile);
    if (session != event.paths.end()) q.loadSession(*session);
    else q.openScenes(event.paths);
    return true;
}

} // namespace mvcl
