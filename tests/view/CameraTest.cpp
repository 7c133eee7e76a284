#include <mvcl/core/Error.h>
#include <mvcl/view/Camera.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

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
