// Controller: the 3D handles of the selected lens (hover, drag, fit) and the lens that follows
// the pointer. The geometry and the drags themselves are pure functions in Gizmo.cpp.

#include "Controller_p.h"

#include <mvcl/lens/PropertyValue.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>

namespace mvcl {

namespace {

/// Faces stay this fraction of the scene's largest side apart; radii stay at least this.
constexpr double kMinimumGizmoSize = 1e-3;

double minimumSize(const LensContext &context) {
    if (context.sceneBounds.isEmpty()) return kMinimumGizmoSize;
    const glm::vec3 e = context.sceneBounds.extent();
    return kMinimumGizmoSize * std::max(double(std::max(e.x, std::max(e.y, e.z))), 1e-30);
}

/// Stages every text of `shape` on `lens` and commits once; restores the lens on error.
void applyShape(Lens &lens, const GizmoShape &shape, const std::string &lensName) {
    const LensState committed = LensState::of(lens);
    try {
        for (const auto &[name, text] : shape.propertyTexts(lens.context())) lens.setPropertyText(name, text);
        lens.commit();
    } catch (const Error &e) {
        committed.applyTo(lens);
        throw Error(lensName, e.problem());
    }
}

Bounds3f boundsOfLayer(const Scene &scene, int layer) {
    Bounds3f bounds;
    for (const TriangleMesh &mesh : scene.meshes)
        if (mesh.layer == layer)
            for (const glm::vec3 &p : mesh.positions) bounds.expand(p);
    for (const Sphere &sphere : scene.spheres)
        if (sphere.layer == layer) {
            bounds.expand(sphere.center - glm::vec3(sphere.radius));
            bounds.expand(sphere.center + glm::vec3(sphere.radius));
        }
    return bounds;
}

Bounds3f boundsOfHit(const Scene &scene, const Hit &hit) {
    Bounds3f bounds;
    if (hit.kind == GeometryKind::Triangle && hit.geometry < scene.meshes.size()) {
        for (const glm::vec3 &p : scene.meshes[hit.geometry].positions) bounds.expand(p);
    } else if (hit.kind == GeometryKind::Sphere && hit.geometry < scene.spheres.size()) {
        const Sphere &sphere = scene.spheres[hit.geometry];
        bounds.expand(sphere.center - glm::vec3(sphere.radius));
        bounds.expand(sphere.center + glm::vec3(sphere.radius));
    }
    return bounds;
}

} // namespace

std::vector<GizmoShape> Controller::gizmoShapes(int index) const {
    const Lens &lens = d->lens(index);
    const std::vector<PropertyValue> values = lens.committedValues();
    const PropertyValues read(lens.properties(), values);
    std::vector<GizmoShape> shapes;
    for (const GizmoDecl &decl : gizmosOf(lens.properties()))
        if (read.isUsed(decl.primary())) shapes.push_back(GizmoShape::read(decl, read, lens.context()));
    return shapes;
}

GizmoView Controller::gizmoView() const { return {d->camera, d->viewSize}; }

std::vector<GizmoHandle> Controller::gizmoHandles(int index) const {
    const std::vector<GizmoShape> shapes = gizmoShapes(index);
    std::vector<GizmoHandle> handles;
    for (size_t i = 0; i < shapes.size(); ++i)
        for (const GizmoHandle &handle : mvcl::gizmoHandles(shapes[i], int(i), gizmoView())) handles.push_back(handle);
    return handles;
}

GizmoDrawing Controller::gizmoDrawing() const {
    GizmoDrawing drawing;
    if (d->selected < 0 || d->selected >= d->stack.size() || !d->stack.lens(d->selected)->snapshot()->enabled)
        return drawing;
    const std::optional<GizmoHandle> active =
        d->drag.kind == DragKind::Gizmo ? std::optional<GizmoHandle>(d->drag.gizmo) : std::nullopt;
    const std::vector<GizmoShape> shapes = gizmoShapes(d->selected);
    for (size_t i = 0; i < shapes.size(); ++i) {
        GizmoDrawing one = mvcl::gizmoDrawing(shapes[i], int(i), gizmoView(), d->hoveredGizmo, active);
        std::ranges::move(one.lines, std::back_inserter(drawing.lines));
        std::ranges::move(one.dots, std::back_inserter(drawing.dots));
    }
    return drawing;
}

std::optional<GizmoHandle> Controller::Private::gizmoAt(const glm::vec2 &pixel) const {
    if (selected < 0 || selected >= stack.size() || !stack.lens(selected)->snapshot()->enabled) return std::nullopt;
    return gizmoHandleAt(q.gizmoShapes(selected), q.gizmoView(), pixel, kGizmoGrabRadius * contentScale);
}

void Controller::Private::startGizmoDrag(int index, const GizmoHandle &handle, const glm::vec2 &pixel,
                                         PointerButton button) {
    Drag started;
    started.kind = DragKind::Gizmo;
    started.button = button;
    started.pressPosition = pixel;
    started.lens = index;
    started.gizmo = handle;
    started.gizmoStart = q.gizmoShapes(index).at(size_t(handle.gizmo));
    started.startRegion = stack.lens(index)->snapshot()->region;
    started.startCamera = camera;
    started.start = captureStep();
    drag = started;
    hoveredGizmo = handle;
    q.beginEditStep(); // press to release is one step
}

void Controller::Private::moveGizmo(const glm::vec2 &pixel, KeyModifier modifiers) {
    Lens &target = lens(drag.lens);
    const GizmoShape shape = dragGizmo(drag.gizmoStart, drag.gizmo, q.gizmoView(), drag.pressPosition, pixel,
                                       modifiers, minimumSize(target.context()));
    applyShape(target, shape, lensName(drag.lens));
    sendLenses();
}

bool Controller::Private::hover(const glm::vec2 &pixel) {
    pointer = pixel;
    bool changed = false;
    if (const int follower = followerIndex(); follower >= 0) {
        // Centred under the pointer, as a drag would move it: no undo step for hovering.
        const LensRegion region = stack.lens(follower)->snapshot()->region;
        const glm::vec2 offset = coordinates().normalizedFromPixel(pixel) - region.center();
        if (offset != glm::vec2(0.f)) {
            commitRegion(follower, translatedRegion(region, offset));
            changed = true;
        }
    }
    const std::optional<GizmoHandle> now = gizmoAt(pixel);
    const bool sameHover = now.has_value() == hoveredGizmo.has_value() && (!now || now->sameGrip(*hoveredGizmo));
    hoveredGizmo = now;
    return changed || !sameHover;
}

void Controller::dragGizmoHandle(int index, std::string_view handleName, const glm::vec2 &offset,
                                 KeyModifier modifiers) {
    if (d->drag.kind != DragKind::None) throw Error(d->lensName(index), "cannot drag a handle during another drag");
    std::vector<std::string> names;
    std::optional<GizmoHandle> found;
    for (const GizmoHandle &candidate : gizmoHandles(index)) {
        if (candidate.gizmo != 0) continue;
        names.push_back(candidate.name());
        if (candidate.name() == handleName) found = candidate;
    }
    if (!found) {
        std::string list;
        for (const std::string &name : names) list += (list.empty() ? "" : ", ") + name;
        throw Error(d->lensName(index), "no handle '" + std::string(handleName) + "' is drawn" +
                                            (list.empty() ? std::string(" (the lens has no 3D handles in use)")
                                                          : " (drawn: " + list + ")"));
    }
    setSelectedLens(index);
    d->startGizmoDrag(index, *found, found->pixel, PointerButton::Left);
    handle(InputEvent::pointerMove(found->pixel + offset, modifiers));
    handle(InputEvent::pointerRelease(found->pixel + offset, PointerButton::Left, modifiers));
}

void Controller::fitLens(int index, LensFit what, int layer, const glm::vec2 &pixel) {
    Lens &target = d->lens(index);
    std::vector<GizmoShape> shapes = gizmoShapes(index);
    auto shape = std::ranges::find_if(shapes, [](const GizmoShape &s) { return s.decl.kind == GizmoDecl::Kind::Box; });
    if (shape == shapes.end())
        shape = std::ranges::find_if(shapes, [](const GizmoShape &s) { return s.decl.kind == GizmoDecl::Kind::Sphere; });
    if (shape == shapes.end()) throw Error(d->lensName(index), "has no box or sphere in use to fit");
    Bounds3f bounds;
    switch (what) {
    case LensFit::All: bounds = d->scene->bounds(); break;
    case LensFit::Layer:
        if (layer < 0 || layer >= kMaxLayers)
            throw Error(d->lensName(index), "cannot fit to layer " + std::to_string(layer) + ": outside 0.." +
                                                std::to_string(kMaxLayers - 1));
        bounds = boundsOfLayer(*d->scene, layer);
        break;
    case LensFit::Object: {
        const std::optional<Hit> hit = d->hitUnder(pixel);
        if (hit) bounds = boundsOfHit(*d->scene, *hit);
        break;
    }
    }
    if (bounds.isEmpty()) throw Error(d->lensName(index), "nothing to fit to there");
    const glm::dvec3 lo(bounds.min), hi(bounds.max);
    shape->center = 0.5 * (lo + hi);
    shape->halfExtent = 0.5 * (hi - lo);
    shape->axes = glm::dmat3(1.0);
    shape->radius = glm::length(shape->halfExtent);
    d->edit(Private::StepKind::Other, [&] {
        applyShape(target, *shape, d->lensName(index));
        d->sendLenses();
    });
}

void Controller::setPointerFollowingLens(int index) {
    if (index >= 0) d->lens(index); // throws for an index outside the stack
    d->pointerFollower = index >= 0 ? std::weak_ptr<const Lens>(d->stack.lens(index)) : std::weak_ptr<const Lens>();
}

int Controller::pointerFollowingLens() const { return d->followerIndex(); }

int Controller::Private::followerIndex() const {
    const std::shared_ptr<const Lens> follower = pointerFollower.lock();
    if (!follower) return -1;
    for (int i = 0; i < stack.size(); ++i)
        if (stack.lens(i) == follower) return i;
    return -1;
}

} // namespace mvcl
