#pragma once
/// \file LensHandle.h
/// The grips a view offers to reshape a lens: the corners and edge midpoints of the bounding
/// box of a rectangle or ellipse, and every vertex of a polygon. Positions are in normalised
/// image coordinates, like the region; the viewer draws them where the controller hit-tests.

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensRegion.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace mvcl {

struct MVCL_EXPORT LensHandle {
    enum class Kind : uint8_t {
        Corner, ///< index 0 top-left, 1 top-right, 2 bottom-right, 3 bottom-left
        Edge,   ///< midpoint; index 0 top, 1 right, 2 bottom, 3 left
        Vertex, ///< a polygon's point `index`
    };

    Kind kind = Kind::Corner;
    int index = 0;
    glm::vec2 position{0.f}; ///< normalised image coordinates

    /// Corners then edge midpoints of a rectangle or ellipse; the points of a polygon.
    static std::vector<LensHandle> of(const LensRegion &region);

    /// `region` (the one the handle was taken from) with this handle moved by `offset`
    /// (normalised). A corner moves two sides of the bounding box and an edge one; the
    /// opposite sides stay where they are, and a side never comes nearer its opposite than
    /// `minimumSize` (normalised per axis), so a region cannot be turned inside out. A vertex
    /// moves alone.
    LensRegion moved(const LensRegion &region, const glm::vec2 &offset, const glm::vec2 &minimumSize) const;

    bool operator==(const LensHandle &other) const = default;
};

} // namespace mvcl
