#pragma once
/// \file LensRegion.h
/// Where a lens sits on the screen: a rectangle, an ellipse or a polygon, in normalised image
/// coordinates (x right, y down, both 0..1, so a lens file works at any resolution), with an
/// optional feathered edge and outline in pixels (the lens's "join" with the outside).

#include <mvcl/core/Export.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace mvcl {

/// Pixel rectangle [x0, x1) × [y0, y1); empty when x0 ≥ x1 or y0 ≥ y1.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool isEmpty() const { return x0 >= x1 || y0 >= y1; }
};

class MVCL_EXPORT LensRegion {
public:
    enum class Shape : uint8_t { Rectangle, Ellipse, Polygon };

    /// The default region: a centred rectangle half the image wide and high.
    LensRegion();
    static LensRegion rectangle(const glm::vec2 &center, const glm::vec2 &size);
    static LensRegion ellipse(const glm::vec2 &center, const glm::vec2 &size);
    /// Points in order (either winding); at least 3. Self-intersecting polygons use even-odd.
    static LensRegion polygon(std::vector<glm::vec2> points);

    Shape shape() const { return m_shape; }
    /// Rectangle/ellipse centre; for a polygon the centre of its bounding box.
    glm::vec2 center() const;
    /// Moves the region (a polygon moves all its points).
    void setCenter(const glm::vec2 &center);
    /// Full width and height (rectangle, ellipse; a polygon's bounding box).
    glm::vec2 size() const;
    /// Rectangle/ellipse only; a polygon is resized by scaling its points about the centre.
    void setSize(const glm::vec2 &size);
    const std::vector<glm::vec2> &points() const { return m_points; }

    /// Width of the soft edge inside the boundary, in pixels; 0 = hard edge.
    float feather() const { return m_feather; }
    void setFeather(float pixels) { m_feather = pixels; }
    /// Outline drawn over the boundary after rendering, in pixels; 0 = none.
    float outlineWidth() const { return m_outlineWidth; }
    void setOutlineWidth(float pixels) { m_outlineWidth = pixels; }
    glm::vec3 outlineColor() const { return m_outlineColor; }
    void setOutlineColor(const glm::vec3 &linearRgb) { m_outlineColor = linearRgb; }

    /// Signed distance in pixels from `pixel` (pixel coordinates, e.g. a pixel centre x + 0.5)
    /// to the boundary in a width × height image; positive inside.
    float signedDistance(const glm::vec2 &pixel, int width, int height) const;
    /// How much of the lens applies at `pixel`: 1 inside (beyond the feather), 0 outside,
    /// a smooth ramp across the feather band.
    float coverage(const glm::vec2 &pixel, int width, int height) const;
    /// Pixels that may have coverage > 0 (or lie under the outline), clipped to the image.
    PixelRect pixelBounds(int width, int height) const;

    /// Row y of the image split for fast rasterisation: pixels outside [x0, x1) have coverage
    /// 0, pixels in [innerX0, innerX1) have coverage exactly 1, the rest need coverage().
    /// Conservative (a pixel may be left to coverage() that turns out 0 or 1); clipped to the
    /// image; an empty row has x0 == x1.
    struct RowSpan {
        int x0 = 0, x1 = 0, innerX0 = 0, innerX1 = 0;
    };
    RowSpan rowSpan(int y, int width, int height) const;
    /// coverage() of the pixels that `span` = rowSpan(y, width, height) leaves to it, [x0,
    /// innerX0) and [innerX1, x1), written to coverage[x − span.x0] (span.x1 − span.x0
    /// entries; those of the inner part are not written). The same values bit for bit, computed
    /// many pixels at a time.
    void edgeCoverage(int y, const RowSpan &span, int width, int height, std::span<float> coverage) const;

    /// Zero width or height: the region covers no pixel and the lens has no effect (not an
    /// error: dragging a lens to nothing is a normal edit).
    bool isEmpty() const;

    /// Throws mvcl::Error("lens region", problem) for non-finite values, a negative size, fewer
    /// than 3 polygon points, negative feather or outline.
    void validate() const;

    bool operator==(const LensRegion &other) const = default;

private:
    Shape m_shape = Shape::Rectangle;
    glm::vec2 m_center{0.5f};
    glm::vec2 m_size{0.5f};
    std::vector<glm::vec2> m_points; // polygon only
    float m_feather = 0.f;
    float m_outlineWidth = 0.f;
    glm::vec3 m_outlineColor{1.f};
};

} // namespace mvcl
