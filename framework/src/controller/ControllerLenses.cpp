// Controller: lens edits and what is under the pointer.

#include "Controller_p.h"

#include <algorithm>
#include <cmath>

namespace mvcl {


// --- Private helpers ---------------------------------------------------------------------------

LensRegion Controller::Private::translatedRegion(const LensRegion &region, const glm::vec2 &offset) {
    if (region.shape() != LensRegion::Shape::Polygon) {
        LensRegion moved = region;
        moved.setCenter(region.center() + offset);
        return moved;
    }
    // Point by point, so that each point moves by exactly the offset.
    std::vector<glm::vec2> points = region.points();
    for (glm::vec2 &point : points) point += offset;
    LensRegion moved = LensRegion::polygon(std::move(points));
    moved.setFeather(region.feather());
    moved.setOutlineWidth(region.outlineWidth());
    moved.setOutlineColor(region.outlineColor());
    return moved;
}

Lens &Controller::Private::lens(int index) const {
    if (index < 0 || index >= stack.size())
        throw Error("lens stack", "no lens at index " + std::to_string(index) + " (the stack has " +
                                      std::to_string(stack.size()) + ")");
    return *stack.lens(index);
}

std::string Controller::Private::lensName(int index) const {
    const Lens &l = lens(index);
    return "lens " + std::to_string(index) + " '" + l.label() + "' (" + l.typeName() + ")";
}

void Controller::Private::commitRegion(int index, const LensRegion &region) {
    Lens &target = lens(index);
    const LensState committed = LensState::of(target);
    try {
        target.setRegion(region);
        target.commit();
    } catch (const Error &e) {
        committed.applyTo(target);
        throw Error(lensName(index), "region: " + e.problem());
    }
    sendLenses();
}

// --- lens edits ----------------------------------------------------------------------------------------

const LensRegistry &Controller::lensRegistry() const { return d->registry; }
const LensStack &Controller::lensStack() const { return d->stack; }
int Controller::lensCount() const { return d->stack.size(); }
int Controller::selectedLens() const { return d->selected; }

void Controller::setSelectedLens(int index) {
    if (index != -1) d->lens(index); // checks the index
    d->selected = index;
}

int Controller::addLens(std::string_view typeName, const glm::vec2 &center) {
    if (d->stack.size() >= LensStack::kMaxLenses)
        throw Error("lens stack", "it holds " + std::to_string(LensStack::kMaxLenses) + " lenses at most");
    std::shared_ptr<Lens> lens = d->registry.create(typeName);
    LensRegion region = lens->region();
    region.setCenter(center);
    lens->setRegion(region);
    lens->commitOrDisable(); // a faulty plugin's lens is added disabled, and reported
    d->edit(Private::StepKind::Other, [&] {
        d->stack.add(std::move(lens));
        d->selected = d->stack.size() - 1;
        d->sendLenses();
    });
    return d->stack.size() - 1;
}

int Controller::duplicateLens(int index) {
    if (d->stack.size() >= LensStack::kMaxLenses)
        throw Error("lens stack", "it holds " + std::to_string(LensStack::kMaxLenses) + " lenses at most");
    LensState copy = LensState::of(d->lens(index));
    copy.region = Private::translatedRegion(copy.region, glm::vec2(kDuplicateOffset));
    std::shared_ptr<Lens> lens = copy.create(d->registry);
    d->edit(Private::StepKind::Other, [&] {
        d->stack.insert(index + 1, std::move(lens));
        d->selected = index + 1;
        d->sendLenses();
    });
    return index + 1;
}

void Controller::removeLens(int index) {
    d->lens(index);
    d->edit(Private::StepKind::Other, [&] {
        d->stack.remove(index);
        if (d->selected == index) d->selected = -1;
        else if (d->selected > index) --d->selected;
        d->sendLenses();
    });
}

void Controller::moveLens(int from, int to) {
    d->lens(from);
    d->lens(to);
    if (from == to) return;
    d->edit(Private::StepKind::Other, [&] {
        d->stack.move(from, to);
        if (d->selected == from) d->selected = to;
        else if (from < d->selected && d->selected <= to) --d->selected;
        else if (to <= d->selected && d->selected < from) ++d->selected;
        d->sendLenses();
    });
}

void Controller::raiseLens(int index) {
    d->lens(index);
    if (index + 1 < d->stack.size()) moveLens(index, index + 1);
}

void Controller::lowerLens(int index) {
    d->lens(index);
    if (index > 0) moveLens(index, index - 1);
}

void Controller::setLensEnabled(int index, bool enabled) {
    Lens &lens = d->lens(index);
    if (lens.snapshot()->enabled == enabled) return;
    d->edit(Private::StepKind::Other, [&] {
        lens.setEnabled(enabled);
        lens.commit();
        d->sendLenses();
    });
}

void Controller::setLensLabel(int index, std::string label) {
    Lens &lens = d->lens(index);
    d->edit(Private::StepKind::Other, [&] { lens.setLabel(std::move(label)); });
}

void Controller::setLensRegion(int index, const LensRegion &region) {
    d->lens(index);
    d->edit(Private::StepKind::Other, [&] { d->commitRegion(index, region); });
}

void Controller::setLensProperty(int index, std::string_view name, std::string_view text) {
    Lens &lens = d->lens(index);
    d->edit(Private::StepKind::Other, [&] {
        const LensState committed = LensState::of(lens);
        try {
            lens.setPropertyText(name, text);
            lens.commit();
        } catch (const Error &e) {
            committed.applyTo(lens); // drop what was staged
            // The lens's own errors name its type; name the lens in the stack instead.
            const bool namesLensType = e.source() == "lens '" + lens.typeName() + "'";
            const std::string problem = namesLensType ? e.problem() : std::string(e.what());
            const std::string property = "property '" + std::string(name) + "': ";
            const bool namesProperty = problem.starts_with(std::string(name) + ": ");
            throw Error(d->lensName(index),
                        namesProperty ? property + problem.substr(name.size() + 2) : property + problem);
        }
        d->sendLenses();
    });
}

std::string Controller::lensProperty(int index, std::string_view name) const {
    const Lens &lens = d->lens(index);
    const PropertyTable &table = lens.properties();
    const std::vector<PropertyValue> values = lens.committedValues();
    for (std::size_t i = 0; i < table.size() && i < values.size(); ++i)
        if (table[i].name == name) return values[i].toString();
    return lens.property(name).toString(); // throws naming the known properties
}

// --- under the pointer -------------------------------------------------------------------------------

int Controller::lensAt(const glm::vec2 &pixel) const {
    const glm::ivec2 size = d->viewSize;
    for (int i = d->stack.size() - 1; i >= 0; --i) {
        const std::shared_ptr<const LensSnapshot> snapshot = d->stack.lens(i)->snapshot();
        if (!snapshot->enabled) continue;
        const LensRegion &region = snapshot->region;
        if (region.coverage(pixel, size.x, size.y) > 0.f) return i;
        // The outline straddles the boundary; grabbing it counts as grabbing the lens.
        if (region.outlineWidth() > 0.f &&
            std::abs(region.signedDistance(pixel, size.x, size.y)) <= 0.5f * region.outlineWidth())
            return i;
    }
    return -1;
}

LensHit Controller::hitTest(const glm::vec2 &pixel) const {
    LensHit hit;
    if (const std::optional<GizmoHandle> gizmo = d->gizmoAt(pixel)) {
        hit.target = LensHit::Target::Gizmo;
        hit.lens = d->selected;
        hit.gizmo = *gizmo;
        return hit;
    }
    if (d->selected >= 0) {
        const ViewCoordinates view = coordinates();
        const float radius = kHandleGrabRadius * d->contentScale;
        float nearest = radius;
        for (const LensHandle &handle : lensHandles(d->selected)) {
            const float distance = glm::length(view.pixelFromNormalized(handle.position) - pixel);
            if (distance <= nearest) {
                nearest = distance;
                hit = {LensHit::Target::Handle, d->selected, handle, {}};
            }
        }
        if (hit.target == LensHit::Target::Handle) return hit;
    }
    if (const int lens = lensAt(pixel); lens >= 0) hit = {LensHit::Target::Lens, lens, {}, {}};
    return hit;
}

std::vector<LensHandle> Controller::lensHandles(int index) const {
    return LensHandle::of(d->lens(index).snapshot()->region);
}

} // namespace mvcl
