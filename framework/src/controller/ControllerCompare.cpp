// Controller: compare mode, a view split by a vertical divider into two lens stacks.

#include "Controller_p.h"

#include <algorithm>
#include <cmath>

namespace mvcl {

void Controller::setCompareEnabled(bool enabled) {
    if (enabled == d->compare.has_value()) return;
    if (d->drag.kind != DragKind::None) d->cancelDrag();
    d->edit(Private::StepKind::Other, [&] {
        if (enabled) {
            // The right side starts as a copy, so that the two differ only by what is changed next.
            Private::Compare compare;
            for (const std::shared_ptr<Lens> &lens : d->stack.lenses()) compare.other.add(LensState::of(*lens).create(d->registry));
            d->compare = std::move(compare);
        } else {
            if (d->compare->side == CompareSide::Right) {
                std::swap(d->stack, d->compare->other);
                d->selected = -1;
            }
            d->compare.reset();
        }
        d->sendLenses();
    });
}

bool Controller::isCompareEnabled() const { return d->compare.has_value(); }

float Controller::compareDivider() const { return d->compare ? d->compare->divider : 0.5f; }

void Controller::setCompareDivider(float x) {
    if (!d->compare) return;
    const float divider = std::clamp(std::isfinite(x) ? x : 0.5f, 0.f, 1.f);
    if (divider == d->compare->divider) return;
    d->edit(Private::StepKind::Other, [&] {
        d->compare->divider = divider;
        d->sendLenses();
    });
}

CompareSide Controller::compareSide() const { return d->compare ? d->compare->side : CompareSide::Left; }

void Controller::setCompareSide(CompareSide side) {
    if (!d->compare || d->compare->side == side) return;
    if (d->drag.kind != DragKind::None) d->cancelDrag();
    std::swap(d->stack, d->compare->other);
    d->compare->side = side;
    d->selected = -1;
}

CompareSide Controller::compareSideAt(const glm::vec2 &pixel) const {
    if (!d->compare) return CompareSide::Left;
    return pixel.x < d->compare->divider * float(d->viewSize.x) ? CompareSide::Left : CompareSide::Right;
}

bool Controller::isOnCompareDivider(const glm::vec2 &pixel) const {
    if (!d->compare) return false;
    return std::abs(pixel.x - d->compare->divider * float(d->viewSize.x)) <= kHandleGrabRadius * d->contentScale;
}

const LensStack &Controller::leftLensStack() const { return d->leftStack(); }

const LensStack &Controller::rightLensStack() const {
    static const LensStack kEmpty;
    return d->compare ? d->rightStack() : kEmpty;
}

} // namespace mvcl
