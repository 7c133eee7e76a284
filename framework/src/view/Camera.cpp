#include <mvcl/view/Camera.h>

#include <mvcl/core/Error.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl {

Camera::Camera() { update(); }

Camera Camera::lookAt(const glm::vec3 &eye, const glm::vec3 &target, const glm::vec3 &up,
                      float verticalFovDegrees) {
    Camera c;
    c.m_eye = eye;
    c.m_target = target;
    c.m_up = up;
    c.m_verticalFovDegrees = verticalFovDegrees;
    c.update();
    return c;
}

Camera Camera::fromDesc(const CameraDesc &desc) {
    return lookAt(desc.eye, desc.target, desc.up, desc.verticalFovDegrees);
}

Camera Camera::framing(const Bounds3f &bounds, float verticalFovDegrees, float aspect) {
    return framing(bounds, verticalFovDegrees, aspect, glm::vec3(0.55f, 0.45f, 1.f), glm::vec3(0.f, 1.f, 0.f));
}

Camera Camera::framing(const Bounds3f &bounds, float verticalFovDegrees, float aspect, const glm::vec3 &towardEye,
                       const glm::vec3 &up) {
    if (bounds.isEmpty()) return lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, verticalFovDegrees);
    const glm::vec3 center = bounds.center();
    const glm::vec3 toEye = glm::length(towardEye) > 0.f ? glm::normalize(towardEye) : glm::vec3(0.f, 0.f, 1.f);
    // Orient first at unit distance, then back off until every box corner is inside both the
    // vertical and the horizontal field of view (tighter than the bounding sphere for long models).
    const Camera oriented = lookAt(center + toEye, center, up, verticalFovDegrees);
    const glm::mat3 &axes = oriented.sceneFromCamera(); // right, up, backward
    const float tanV = oriented.m_tanHalfFov;
    const float tanH = tanV * aspect;
    float distance = 0.f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 c = corner - center;
        const float x = std::abs(glm::dot(c, axes[0]));
        const float y = std::abs(glm::dot(c, axes[1]));
        const float towardEye = glm::dot(c, axes[2]);
        distance = std::max({distance, towardEye + x / tanH, towardEye + y / tanV});
    }
    distance = std::max(distance * 1.08f, 1e-30f);
    return lookAt(center + distance * toEye, center, up, verticalFovDegrees);
}

void Camera::generateRays(std::span<const glm::vec2> positions, int width, int height, std::span<Ray> rays) const {
    if (rays.size() < positions.size())
        throw Error("camera", "generateRays needs room for " + std::to_string(positions.size()) + " rays, not " +
                                  std::to_string(rays.size()));
    std::size_t i = 0;
#if defined(__SSE2__)
    // generateRay()'s operations in its order, four rays per instruction: every step is an IEEE
    // operation rounded once (no fused multiply-add, no reciprocal estimate), so the bits match.
    const float aspect = float(width) / float(height);
    const float spread = 2.f * m_tanHalfFov / float(height);
    const __m128 two = _mm_set1_ps(2.f), one = _mm_set1_ps(1.f), minusOne = _mm_set1_ps(-1.f);
    const __m128 w = _mm_set1_ps(float(width)), h = _mm_set1_ps(float(height));
    const __m128 tanHalfFov = _mm_set1_ps(m_tanHalfFov), aspects = _mm_set1_ps(aspect);
    const glm::mat3 &m = m_sceneFromCamera;
    for (; i + 4 <= positions.size(); i += 4) {
        const glm::vec2 *p = positions.data() + i;
        const __m128 x = _mm_setr_ps(p[0].x, p[1].x, p[2].x, p[3].x);
        const __m128 y = _mm_setr_ps(p[0].y, p[1].y, p[2].y, p[3].y);
        const __m128 sx =
            _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(_mm_div_ps(_mm_mul_ps(two, x), w), one), tanHalfFov), aspects);
        const __m128 sy = _mm_mul_ps(_mm_sub_ps(one, _mm_div_ps(_mm_mul_ps(two, y), h)), tanHalfFov);
        __m128 d[3];
        for (int c = 0; c < 3; ++c) // glm's mat3 × vec3: m[0][c]·x + m[1][c]·y + m[2][c]·z, z = −1
            d[c] = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(m[0][c]), sx), _mm_mul_ps(_mm_set1_ps(m[1][c]), sy)),
                              _mm_mul_ps(_mm_set1_ps(m[2][c]), minusOne));
        // glm::normalize: v · (1 / √(dot(v, v))), the dot summed x, y, z.
        const __m128 lengthSquared =
            _mm_add_ps(_mm_add_ps(_mm_mul_ps(d[0], d[0]), _mm_mul_ps(d[1], d[1])), _mm_mul_ps(d[2], d[2]));
        const __m128 inverseLength = _mm_div_ps(one, _mm_sqrt_ps(lengthSquared));
        alignas(16) float direction[3][4];
        for (int c = 0; c < 3; ++c) _mm_store_ps(direction[c], _mm_mul_ps(d[c], inverseLength));
        for (int j = 0; j < 4; ++j) {
            Ray &ray = rays[i + std::size_t(j)];
            ray.origin = m_eye;
            ray.direction = {direction[0][j], direction[1][j], direction[2][j]};
            ray.coneWidth = 0.f;
            ray.coneSpread = spread;
        }
    }
#endif
    for (; i < positions.size(); ++i) rays[i] = generateRay(positions[i].x, positions[i].y, width, height);
}

std::optional<Camera::RasterRect> Camera::rasterFootprint(const Bounds3f &box, int width, int height) const {
    if (box.isEmpty()) return RasterRect{1.f, 1.f, 0.f, 0.f};
    // generateRay() maps raster (x, y) to the direction M·(sx, sy, −1) with
    // sx = (2x/w − 1)·tan·aspect and sy = (1 − 2y/h)·tan: a point q = Mᵀ(p − eye) in camera space
    // (M is a rotation, its transpose its inverse up to float rounding) lies on the ray through
    // x = (qx/(−qz)/(tan·aspect) + 1)·w/2, y = (1 − qy/(−qz)/tan)·h/2. A convex box projects
    // into the hull of its corners' projections.
    const double aspect = double(width) / double(height), tanHalf = double(m_tanHalfFov);
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1 ? box.max : box.min).x, (corner & 2 ? box.max : box.min).y,
                           (corner & 4 ? box.max : box.min).z);
        const glm::dvec3 rel = p - glm::dvec3(m_eye);
        double q[3];
        for (int axis = 0; axis < 3; ++axis) q[axis] = glm::dot(glm::dvec3(m_sceneFromCamera[axis]), rel);
        // In front of the eye by a clear margin, or the projection is unbounded.
        const double depth = -q[2];
        if (!(depth > 1e-4 * glm::length(rel))) return std::nullopt;
        const double x = (q[0] / depth / (tanHalf * aspect) + 1.0) * 0.5 * double(width);
        const double y = (1.0 - q[1] / depth / tanHalf) * 0.5 * double(height);
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
    }
    constexpr double kMargin = 2.0;
    return RasterRect{float(x0 - kMargin), float(y0 - kMargin), float(x1 + kMargin), float(y1 + kMargin)};
}

void Camera::update() {
    glm::vec3 forward = m_target - m_eye;
    if (!(glm::length(forward) > 0.f)) forward = {0.f, 0.f, -1.f};
    forward = glm::normalize(forward);
    glm::vec3 right = glm::cross(forward, m_up);
    if (!(glm::length(right) > 1e-6f)) // up parallel to the view: pick any perpendicular
        right = glm::cross(forward, std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    right = glm::normalize(right);
    const glm::vec3 trueUp = glm::cross(right, forward);
    m_sceneFromCamera = glm::mat3(right, trueUp, -forward);
    m_tanHalfFov = std::tan(glm::radians(std::clamp(m_verticalFovDegrees, 1e-3f, 179.f)) * 0.5f);
}

} // namespace mvcl
