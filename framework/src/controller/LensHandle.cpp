#include <mvcl/controller/LensHandle.h>

#include <algorithm>

namespace mvcl {

namespace {

/// Which sides of the bounding box a box handle moves: −1 the low side (left, top), +1 the
/// high side (right, bottom), 0 neither, per axis.
glm::vec2 boxSides(LensHandle::Kind kind, int index) {
    static constexpr glm::vec2 kCorners[] = {{-1.f, -1.f}, {1.f, -1.f}, {1.f, 1.f}, {-1.f, 1.f}};
    static constexpr glm::vec2 kEdges[] = {{0.f, -1.f}, {1.f, 0.f}, {0.f, 1.f}, {-1.f, 0.f}};
    const int i = std::clamp(index, 0, 3);
    return kind == LensHandle::Kind::Corner ? kCorners[i] : kEdges[i];
}

} // namespace

std::vector<LensHandle> LensHandle::of(const LensRegion &region) {
    std::vector<LensHandle> handles;
    if (region.shape() == LensRegion::Shape::Polygon) {
        for (std::size_t i = 0; i < region.points().size(); ++i)
            handles.push_back({Kind::Vertex, int(i), region.points()[i]});
        return handles;
    }
    const glm::vec2 center = region.center(), half = 0.5f * region.size();
    for (const Kind kind : {Kind::Corner, Kind::Edge})
        for (int i = 0; i < 4; ++i) handles.push_back({kind, i, center + boxSides(kind, i) * half});
    return handles;
}

LensRegion LensHandle::moved(const LensRegion &region, const glm::vec2 &offset, const glm::vec2 &minimumSize) const {
    LensRegion result = region;
    if (kind == Kind::Vertex) {
        if (region.shape() != LensRegion::Shape::Polygon || index < 0 || index >= int(region.points().size()))
            return result;
        std::vector<glm::vec2> points = region.points();
        points[std::size_t(index)] += offset;
        result = LensRegion::polygon(std::move(points));
        result.setFeather(region.feather());
        result.setOutlineWidth(region.outlineWidth());
        result.setOutlineColor(region.outlineColor());
        return result;
    }
    if (region.shape() == LensRegion::Shape::Polygon) return result;
    const glm::vec2 sides = boxSides(kind, index);
    glm::vec2 center = region.center(), size = region.size();
    for (int axis = 0; axis < 2; ++axis) {
        if (sides[axis] == 0.f) continue;
        // The opposite side stays; the moved side keeps at least minimumSize from it.
        const float fixedSide = center[axis] - sides[axis] * 0.5f * size[axis];
        const float extent = std::max(size[axis] + sides[axis] * offset[axis], minimumSize[axis]);
        size[axis] = extent;
        center[axis] = fixedSide + sides[axis] * 0.5f * extent;
    }
    result.setCenter(center);
    result.setSize(size);
    return result;
}

} // namespace mvcl
