#include <mvcl/lens/LensRegion.h>

#include "EllipseCoverage4_p.h"
#include "EllipseRampBatch_p.h"

#include <mvcl/core/Error.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mvcl {

namespace {

constexpr float kFarOutside = -std::numeric_limits<float>::infinity();

bool isFinite(const glm::vec2 &v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool isFinite(const glm::vec3 &v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

struct Bounds {
    glm::vec2 lower{0.f};
    glm::vec2 upper{0.f};
};

Bounds pointBounds(const std::vector<glm::vec2> &points) {
    if (points.empty()) return {};
    Bounds bounds{points.front(), points.front()};
    for (const glm::vec2 &p : points) {
        bounds.lower = glm::min(bounds.lower, p);
        bounds.upper = glm::max(bounds.upper, p);
    }
    return bounds;
}

// Exact signed distance to an axis-aligned box of half extents `half` centred at the origin,
// positive inside.
float boxSignedDistance(const glm::vec2 &p, const glm::vec2 &half) {
    const glm::vec2 d = glm::abs(p) - half;
    const float outside = glm::length(glm::max(d, glm::vec2(0.f)));
    const float inside = std::min(std::max(d.x, d.y), 0.f);
    return -(outside + inside);
}

// Distance to the nearest point of the ellipse, found by a few trig-free Newton-like steps on
// the evolute (Chatfield's method): accurate to a small fraction of a pixel everywhere, so a
// feathered edge has the same width all around even on a thin ellipse.
float ellipseSignedDistance(const glm::vec2 &p, const glm::vec2 &radii) {
    if (!(radii.x > 0.f && radii.y > 0.f)) return kFarOutside;
    const glm::vec2 q = glm::abs(p); // by symmetry, work in the first quadrant
    const float a = radii.x, b = radii.y;
    glm::vec2 t(0.70710678f); // (cos, sin) of the parameter of the nearest point
    for (int iteration = 0; iteration < 4; ++iteration) {
        const glm::vec2 onEllipse(a * t.x, b * t.y);
        const glm::vec2 evolute((a * a - b * b) * t.x * t.x * t.x / a,
                                (b * b - a * a) * t.y * t.y * t.y / b);
        const float r = glm::length(onEllipse - evolute);
        const float toPoint = glm::length(q - evolute);
        const glm::vec2 towards = toPoint > 0.f ? (q - evolute) * (r / toPoint) : glm::vec2(0.f);
        t = glm::clamp((towards + evolute) / radii, glm::vec2(0.f), glm::vec2(1.f));
        const float norm = glm::length(t);
        t = norm > 0.f ? t / norm : glm::vec2(1.f, 0.f);
    }
    const float distance = glm::length(q - glm::vec2(a * t.x, b * t.y));
    const glm::vec2 scaled = q / radii;
    return glm::dot(scaled, scaled) <= 1.f ? distance : -distance;
}

float segmentDistance(const glm::vec2 &p, const glm::vec2 &a, const glm::vec2 &b) {
    const glm::vec2 ab = b - a;
    const float lengthSquared = glm::dot(ab, ab);
    const float t = lengthSquared > 0.f ? std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.f, 1.f)
                                        : 0.f;
    return glm::length(p - (a + t * ab));
}

// Distance to the nearest edge, positive where a ray from p crosses the boundary an odd number
// of times (the even-odd rule, so either winding and self-intersections behave alike).
// `points` are normalised; `scale` takes them to pixels.
float polygonSignedDistance(const glm::vec2 &p, const std::vector<glm::vec2> &points,
                            const glm::vec2 &scale) {
    if (points.size() < 2) return kFarOutside;
    float distance = std::numeric_limits<float>::infinity();
    bool inside = false;
    for (size_t i = 0, j = points.size() - 1; i < points.size(); j = i++) {
        const glm::vec2 a = points[j] * scale;
        const glm::vec2 b = points[i] * scale;
        distance = std::min(distance, segmentDistance(p, a, b));
        if ((a.y > p.y) != (b.y > p.y)) {
            const float crossingX = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if (p.x < crossingX) inside = !inside;
        }
    }
    return inside ? distance : -distance;
}

} // namespace

LensRegion::LensRegion() = default;

LensRegion LensRegion::rectangle(const glm::vec2 &center, const glm::vec2 &size) {
    LensRegion region;
    region.m_shape = Shape::Rectangle;
    region.m_center = center;
    region.m_size = size;
    return region;
}

LensRegion LensRegion::ellipse(const glm::vec2 &center, const glm::vec2 &size) {
    LensRegion region = rectangle(center, size);
    region.m_shape = Shape::Ellipse;
    return region;
}

LensRegion LensRegion::polygon(std::vector<glm::vec2> points) {
    LensRegion region;
    region.m_shape = Shape::Polygon;
    region.m_points = std::move(points);
    return region;
}

glm::vec2 LensRegion::center() const {
    if (m_shape != Shape::Polygon) return m_center;
    const Bounds bounds = pointBounds(m_points);
    return 0.5f * (bounds.lower + bounds.upper);
}

void LensRegion::setCenter(const glm::vec2 &center) {
    if (m_shape != Shape::Polygon) {
        m_center = center;
        return;
    }
    const glm::vec2 offset = center - this->center();
    for (glm::vec2 &p : m_points) p += offset;
}

glm::vec2 LensRegion::size() const {
    if (m_shape != Shape::Polygon) return m_size;
    const Bounds bounds = pointBounds(m_points);
    return bounds.upper - bounds.lower;
}

void LensRegion::setSize(const glm::vec2 &size) {
    if (m_shape != Shape::Polygon) {
        m_size = size;
        return;
    }
    const glm::vec2 oldSize = this->size();
    const glm::vec2 pivot = center();
    // A flat axis cannot be scaled to a size; it stays as it is.
    const glm::vec2 scale(oldSize.x > 0.f ? size.x / oldSize.x : 1.f,
                          oldSize.y > 0.f ? size.y / oldSize.y : 1.f);
    for (glm::vec2 &p : m_points) p = pivot + (p - pivot) * scale;
}

float LensRegion::signedDistance(const glm::vec2 &pixel, int width, int height) const {
    const glm::vec2 imageSize{float(width), float(height)};
    switch (m_shape) {
    case Shape::Rectangle:
        return boxSignedDistance(pixel - m_center * imageSize, 0.5f * m_size * imageSize);
    case Shape::Ellipse:
        return ellipseSignedDistance(pixel - m_center * imageSize, 0.5f * m_size * imageSize);
    case Shape::Polygon: return polygonSignedDistance(pixel, m_points, imageSize);
    }
    return kFarOutside;
}

#if defined(__SSE2__)
namespace {
// The ellipse in pixels when coverage() would run its nearest-point iteration on it (feathered,
// radii > 0); these go through the 4-wide kernel.
std::optional<detail::EllipseCoverageShape> featheredEllipse(LensRegion::Shape shape, const glm::vec2 &center,
                                                             const glm::vec2 &size, float feather, int width,
                                                             int height) {
    if (shape != LensRegion::Shape::Ellipse || !(feather > 0.f)) return std::nullopt;
    const glm::vec2 imageSize{float(width), float(height)};
    const glm::vec2 c = center * imageSize;
    const glm::vec2 radii = 0.5f * size * imageSize;
    if (!(radii.x > 0.f && radii.y > 0.f)) return std::nullopt;
    return detail::EllipseCoverageShape{c.x, c.y, radii.x, radii.y, feather};
}
} // namespace
#endif

bool LensRegion::isEmpty() const {
    const glm::vec2 extent = size();
    return !(extent.x > 0.f && extent.y > 0.f);
}

float LensRegion::coverage(const glm::vec2 &pixel, int width, int height) const {
    if (isEmpty()) return 0.f;
#if defined(__SSE2__)
    if (const auto ellipse = featheredEllipse(m_shape, m_center, m_size, m_feather, width, height)) {
        const __m128 x[1] = {_mm_set1_ps(pixel.x)}, y = _mm_set1_ps(pixel.y);
        int unsettled = 0;
        const __m128 settled = detail::ellipseSettled4(*ellipse, x[0], y, unsettled);
        if (unsettled == 0) return _mm_cvtss_f32(settled);
        __m128 ramp[1];
        detail::ellipseRamp4(*ellipse, x, y, ramp);
        return _mm_cvtss_f32(ramp[0]);
    }
#endif
    if (m_shape == Shape::Ellipse) {
        // Most pixels of an ellipse are far from its edge: the implicit equation settles them
        // without the nearest-point iteration. A point at normalised radius r < 1 is at least
        // (1 − r)·(smaller radius) inside, the gap between the ellipse and its copy scaled by r.
        const glm::vec2 radii = 0.5f * m_size * glm::vec2(float(width), float(height));
        const glm::vec2 scaled = glm::abs(pixel - m_center * glm::vec2(float(width), float(height))) / radii;
        const float radiusSquared = glm::dot(scaled, scaled);
        if (!(radiusSquared <= 1.f)) return 0.f;
        if (!(m_feather > 0.f)) return 1.f;
        if ((1.f - std::sqrt(radiusSquared)) * std::min(radii.x, radii.y) >= m_feather) return 1.f;
    }
    const float distance = signedDistance(pixel, width, height);
    if (!(m_feather > 0.f)) return distance >= 0.f ? 1.f : 0.f;
    if (!(distance > 0.f)) return 0.f; // also catches NaN
    const float t = std::min(distance / m_feather, 1.f);
    return t * t * (3.f - 2.f * t);
}


void LensRegion::edgeCoverage(int y, const RowSpan &span, int width, int height, std::span<float> coverage) const {
    const std::pair<int, int> parts[2] = {{span.x0, span.innerX0}, {span.innerX1, span.x1}};
#if defined(__SSE2__)
    if (const auto ellipse = featheredEllipse(m_shape, m_center, m_size, m_feather, width, height)) {
        const __m128 centreY = _mm_set1_ps(float(y) + 0.5f);
        detail::EllipseRampBatch batch(*ellipse, y, span.x0, coverage);
        for (const auto &[from, to] : parts) {
            for (int x = from; x < to; x += 4) {
                const __m128 centreX =
                    _mm_add_ps(_mm_cvtepi32_ps(_mm_setr_epi32(x, x + 1, x + 2, x + 3)), _mm_set1_ps(0.5f));
                int unsettled = 0;
                alignas(16) float settled[4];
                _mm_store_ps(settled, detail::ellipseSettled4(*ellipse, centreX, centreY, unsettled));
                const int lanes = std::min(4, to - x);
                for (int i = 0; i < lanes; ++i) {
                    coverage[std::size_t(x + i - span.x0)] = settled[i];
                    if ((unsettled >> i) & 1) batch.add(x + i);
                }
            }
        }
        batch.flush();
        return;
    }
#endif
    for (const auto &[from, to] : parts)
        for (int x = from; x < to; ++x)
            coverage[std::size_t(x - span.x0)] = this->coverage({float(x) + 0.5f, float(y) + 0.5f}, width, height);
}

LensRegion::RowSpan LensRegion::rowSpan(int y, int width, int height) const {
    const PixelRect bounds = pixelBounds(width, height);
    RowSpan span;
    if (y < bounds.y0 || y >= bounds.y1) return span;
    span.x0 = span.innerX0 = span.innerX1 = bounds.x0;
    span.x1 = bounds.x1;
    if (m_shape == Shape::Polygon) return span; // every pixel of the box goes to coverage()

    const glm::vec2 imageSize{float(width), float(height)};
    const glm::vec2 c = m_center * imageSize;
    const glm::vec2 half = 0.5f * m_size * imageSize;
    const float feather = std::max(m_feather, 0.f);
    const float dy = std::abs(float(y) + 0.5f - c.y);
    // Pixel x has its centre x + 0.5 in [from, to] for x in [firstPixel(from), endPixel(to)),
    // clamped in floating point so that far-off shapes cannot overflow an int.
    const auto clampToRow = [&](double x) { return std::clamp(x, double(bounds.x0), double(bounds.x1)); };
    const auto firstPixel = [&](double from) { return int(clampToRow(std::ceil(from - 0.5))); };
    const auto endPixel = [&](double to) { return int(clampToRow(std::floor(to - 0.5) + 1.0)); };

    if (m_shape == Shape::Ellipse) {
        // Outside the ellipse coverage is 0, so the row ends where the ellipse does, not at the
        // bounding box (which leaves a quarter of the box to coverage()). The margin, a pixel
        // plus 10⁻⁵ of the coordinates' size, outgrows the rounding of coverage()'s implicit
        // equation even for huge or far-off ellipses.
        const double marginX = 1.0 + 1e-5 * (double(half.x) + std::abs(double(c.x)));
        const double marginY = 1.0 + 1e-5 * (double(half.y) + std::abs(double(c.y)));
        const double nearDy = std::max(0.0, double(dy) - marginY);
        double outerHalfWidth = -1.0;
        if (nearDy < double(half.y)) {
            const double v = nearDy / double(half.y);
            outerHalfWidth = double(half.x) * std::sqrt(1.0 - v * v) + marginX;
        }
        if (!(outerHalfWidth > 0.0)) { // also NaN: a degenerate ellipse covers nothing
            span.x1 = span.x0;
            return span;
        }
        span.x0 = span.innerX0 = span.innerX1 = firstPixel(double(c.x) - outerHalfWidth);
        span.x1 = std::max(span.x0, endPixel(double(c.x) + outerHalfWidth));
    }

    // The fully covered part of the row: inside the shape shrunk by the feather, less a pixel
    // of margin each side so that rounding never claims a pixel coverage() would not.
    float innerHalfWidth = -1.f;
    if (m_shape == Shape::Rectangle) {
        if (dy + feather + 1.f <= half.y) innerHalfWidth = half.x - feather - 1.f;
    } else {
        // Points inside the ellipse scaled by k lie at least (1 − k)·min radius inside.
        const float k = 1.f - feather / std::min(half.x, half.y);
        const float v = k > 0.f ? (dy + 1.f) / (half.y * k) : 2.f;
        if (v < 1.f) innerHalfWidth = half.x * k * std::sqrt(1.f - v * v) - 1.f;
    }
    if (innerHalfWidth <= 0.f) return span;
    // Pixel x is inside when its centre x + 0.5 lies in [c.x − w, c.x + w].
    const int innerX0 = std::max(span.x0, firstPixel(double(c.x - innerHalfWidth)));
    const int innerX1 = std::min(span.x1, endPixel(double(c.x + innerHalfWidth)));
    if (innerX0 < innerX1) {
        span.innerX0 = innerX0;
        span.innerX1 = innerX1;
    }
    return span;
}

PixelRect LensRegion::pixelBounds(int width, int height) const {
    if (isEmpty()) return {};
    Bounds bounds;
    if (m_shape == Shape::Polygon) {
        if (m_points.empty()) return {};
        bounds = pointBounds(m_points);
    } else {
        bounds = {m_center - 0.5f * m_size, m_center + 0.5f * m_size};
    }
    const glm::vec2 imageSize{float(width), float(height)};
    const float margin = 0.5f * std::max(m_outlineWidth, 0.f) + 1.f;
    const glm::vec2 lower = bounds.lower * imageSize - margin;
    const glm::vec2 upper = bounds.upper * imageSize + margin;
    if (!isFinite(lower) || !isFinite(upper)) return {};
    // Clamp in float before converting so far-off regions cannot overflow an int.
    const auto toPixel = [](float value, int limit) {
        return int(std::clamp(value, 0.f, float(limit)));
    };
    PixelRect rect;
    rect.x0 = toPixel(std::floor(lower.x), width);
    rect.y0 = toPixel(std::floor(lower.y), height);
    rect.x1 = toPixel(std::ceil(upper.x), width);
    rect.y1 = toPixel(std::ceil(upper.y), height);
    return rect;
}

void LensRegion::validate() const {
    const char *source = "lens region";
    if (!std::isfinite(m_feather) || m_feather < 0.f)
        throw Error(source, "feather must be a finite width ≥ 0 px, got " + std::to_string(m_feather));
    if (!std::isfinite(m_outlineWidth) || m_outlineWidth < 0.f)
        throw Error(source, "outline width must be a finite width ≥ 0 px, got " +
                                std::to_string(m_outlineWidth));
    if (!isFinite(m_outlineColor)) throw Error(source, "outline colour is not finite");
    if (m_shape == Shape::Polygon) {
        if (m_points.size() < 3)
            throw Error(source, "a polygon needs at least 3 points, got " +
                                    std::to_string(m_points.size()));
        for (const glm::vec2 &p : m_points)
            if (!isFinite(p)) throw Error(source, "a polygon point is not finite");
        return; // a polygon without area is an empty region (isEmpty), not an error
    }
    if (!isFinite(m_center)) throw Error(source, "centre is not finite");
    if (!isFinite(m_size) || !(m_size.x >= 0.f && m_size.y >= 0.f))
        throw Error(source, "size must be finite and ≥ 0, got " + std::to_string(m_size.x) + " x " +
                                std::to_string(m_size.y));
}

} // namespace mvcl
