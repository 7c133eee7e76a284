#include <mvcl/core/Error.h>
#include <mvcl/view/Camera.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <utility>
#include <vector>

using namespace mvcl;

TEST(Camera, CentreRayLooksAtTargetAndDirectionsAreUnit) {
    const Camera c = Camera::lookAt({1.f, 2.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 50.f);
    const Ray centre = c.generateRay(50.f, 25.f, 100, 50);
    const glm::vec3 expected = glm::normalize(glm::vec3(-1.f, -2.f, -3.f));
    EXPECT_NEAR(glm::dot(centre.direction, expected), 1.f, 1e-6f);
    for (float x : {0.f, 37.5f, 100.f})
        for (float y : {0.f, 50.f})
            EXPECT_NEAR(glm::length(c.generateRay(x, y, 100, 50).direction), 1.f, 1e-6f);
}

TEST(Camera, TopOfTheImageIsUpAndLeftIsLeft) {
    const Camera c = Camera::lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 60.f);
    EXPECT_GT(c.generateRay(50.f, 0.f, 100, 100).direction.y, 0.f);
    EXPECT_LT(c.generateRay(0.f, 50.f, 100, 100).direction.x, 0.f);
}

TEST(Camera, VerticalFovSpansTheImageHeight) {
    const Camera c = Camera::lookAt({0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, {0.f, 1.f, 0.f}, 90.f);
    const Ray top = c.generateRay(50.f, 0.f, 100, 100);
    EXPECT_NEAR(top.direction.y / -top.direction.z, 1.f, 1e-5f); // tan(45°)
}

TEST(Camera, FramingSeesTheWholeBoxAndSurvivesDegenerateInput) {
    Bounds3f b;
    b.expand({-1.f, -1.f, -1.f});
    b.expand({1.f, 1.f, 1.f});
    const Camera c = Camera::framing(b, 40.f, 4.f / 3.f);
    EXPECT_GT(glm::length(c.eye() - b.center()), std::sqrt(3.f));
    const Camera up = Camera::lookAt({0.f, 5.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    const Ray r = up.generateRay(10.f, 10.f, 20, 20);
    EXPECT_TRUE(std::isfinite(r.direction.x) && std::isfinite(r.direction.y) && std::isfinite(r.direction.z));
    const Camera empty = Camera::framing(Bounds3f{}, 40.f, 1.f);
    EXPECT_TRUE(std::isfinite(empty.eye().z));
}

TEST(Camera, GenerateRaysGivesTheSameBitsAsGenerateRayOneByOne) {
    // Odd counts exercise the four-wide path and its scalar tail; odd sizes and oblique cameras
    // make every division and square root round.
    const Camera cameras[] = {Camera::lookAt({1.3f, 2.7f, -3.1f}, {0.2f, -0.4f, 0.9f}, {0.1f, 1.f, 0.3f}, 37.f),
                              Camera::lookAt({0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 90.f)};
    for (const Camera &c : cameras)
        for (int n : {1, 4, 7, 16}) {
            std::vector<glm::vec2> positions;
            for (int i = 0; i < n; ++i) positions.push_back({0.37f + 61.3f * float(i), 399.9f - 23.7f * float(i)});
            std::vector<Ray> rays(static_cast<size_t>(n));
            c.generateRays(positions, 803, 401, rays);
            for (int i = 0; i < n; ++i) {
                const Ray one = c.generateRay(positions[size_t(i)].x, positions[size_t(i)].y, 803, 401);
                const Ray &batch = rays[size_t(i)];
                for (int k = 0; k < 3; ++k) {
                    EXPECT_EQ(batch.origin[k], one.origin[k]);
                    EXPECT_EQ(batch.direction[k], one.direction[k]) << "ray " << i << " of " << n << ", component " << k;
                }
                EXPECT_EQ(batch.coneWidth, one.coneWidth);
                EXPECT_EQ(batch.coneSpread, one.coneSpread);
            }
        }
}

TEST(Camera, GenerateRaysRefusesTooFewRays) {
    const Camera c;
    const std::vector<glm::vec2> positions(5, glm::vec2(1.f, 1.f));
    std::vector<Ray> rays(4);
    EXPECT_THROW(c.generateRays(positions, 10, 10, rays), Error);
}

namespace {

/// Whether the ray meets the box, in double (slab test).
bool meetsBox(const Ray &ray, const Bounds3f &box) {
    double tNear = 0.0, tFar = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
        const double o = ray.origin[axis], d = ray.direction[axis];
        if (d == 0.0) {
            if (o < box.min[axis] || o > box.max[axis]) return false;
            continue;
        }
        double t0 = (double(box.min[axis]) - o) / d, t1 = (double(box.max[axis]) - o) / d;
        if (t0 > t1) std::swap(t0, t1);
        tNear = std::max(tNear, t0);
        tFar = std::min(tFar, t1);
    }
    return tNear <= tFar;
}

} // namespace

// The renderer leaves whole blocks of pixels outside the footprint of the scene's bounds
// untraced: no ray through a position outside it may meet the box.
TEST(Camera, RasterFootprintHoldsEveryRayThatMeetsTheBox) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.f, 1.f);
    const int width = 64, height = 48;
    int bounded = 0, met = 0;
    for (int trial = 0; trial < 60; ++trial) {
        Bounds3f box;
        const glm::vec3 centre{unit(rng), unit(rng), unit(rng)};
        box.expand(centre - glm::abs(glm::vec3(unit(rng), unit(rng), unit(rng))) * 0.5f);
        box.expand(centre + glm::abs(glm::vec3(unit(rng), unit(rng), unit(rng))) * 0.5f);
        const glm::vec3 eye = 4.f * glm::vec3(unit(rng), unit(rng), unit(rng));
        const Camera camera = Camera::lookAt(eye, centre + 0.8f * glm::vec3(unit(rng), unit(rng), unit(rng)),
                                             {0.f, 1.f, 0.f}, 20.f + 60.f * std::abs(unit(rng)));
        const std::optional<Camera::RasterRect> rect = camera.rasterFootprint(box, width, height);
        if (!rect) continue; // the box reaches beside or behind the eye
        ++bounded;
        for (float y = 0.f; y < float(height); y += 0.37f)
            for (float x = 0.f; x < float(width); x += 0.37f) {
                if (!meetsBox(camera.generateRay(x, y, width, height), box)) continue;
                ++met;
                ASSERT_TRUE(x >= rect->x0 && x <= rect->x1 && y >= rect->y0 && y <= rect->y1)
                    << "trial " << trial << " at " << x << ", " << y;
            }
    }
    EXPECT_GT(bounded, 20);
    EXPECT_GT(met, 1000);
}

TEST(Camera, RasterFootprintOfABoxInViewBehindOrAroundTheEye) {
    const Camera camera = Camera::lookAt({0.f, 0.f, 10.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    Bounds3f small;
    small.expand({-0.5f, -0.5f, -0.5f});
    small.expand({0.5f, 0.5f, 0.5f});
    const std::optional<Camera::RasterRect> rect = camera.rasterFootprint(small, 100, 100);
    ASSERT_TRUE(rect);
    // Centred; its near face (0.5 from the centre at depth 9.5) spans 2 · 50 · 0.5/(9.5 · tan 20°)
    // pixels, plus the margin of two pixels on each side.
    const float span = float(100.0 * 0.5 / (9.5 * std::tan(20.0 * 3.14159265358979 / 180.0))) + 4.f;
    EXPECT_NEAR(rect->x0 + rect->x1, 100.f, 0.01f);
    EXPECT_NEAR(rect->y0 + rect->y1, 100.f, 0.01f);
    EXPECT_NEAR(rect->x1 - rect->x0, span, 0.01f);
    EXPECT_NEAR(rect->y1 - rect->y0, span, 0.01f);
    Bounds3f behind;
    behind.expand({-1.f, -1.f, 11.f});
    behind.expand({1.f, 1.f, 12.f});
    EXPECT_FALSE(camera.rasterFootprint(behind, 100, 100));
    Bounds3f around;
    around.expand({-1.f, -1.f, 9.f});
    around.expand({1.f, 1.f, 11.f});
    EXPECT_FALSE(camera.rasterFootprint(around, 100, 100));
    const std::optional<Camera::RasterRect> none = camera.rasterFootprint(Bounds3f{}, 100, 100);
    ASSERT_TRUE(none);
    EXPECT_LT(none->x1, none->x0);
}
