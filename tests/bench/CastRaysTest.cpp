// The rays of `mvcl-bench cast`: exactly the documented pinhole rays (row 0 at the top, pixel
// centres, the vertical field of view in degrees), camera text that reads back to itself, clear
// errors for bad cameras, and a cast on a plane whose every distance is known.

#include "CastRays.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace mvcl::bench {
namespace {

CastCamera lookDownMinusZ(double fovDegrees) {
    CastCamera c;
    c.eye = {0.0, 0.0, 0.0};
    c.target = {0.0, 0.0, -1.0};
    c.up = {0.0, 1.0, 0.0};
    c.verticalFovDegrees = fovDegrees;
    return c;
}

TEST(CastRays, PixelCentresRowZeroAtTheTopFieldOfViewInDegrees) {
    const std::vector<Ray> rays = castRays(lookDownMinusZ(90.0), 3, 3, glm::dvec3(0.0));
    ASSERT_EQ(rays.size(), 9u);
    // The centre pixel of a 3×3 image looks straight ahead.
    EXPECT_EQ(rays[4].direction, glm::vec3(0.f, 0.f, -1.f));
    // Row 0 is the top row: its rays point up; the left column points left.
    EXPECT_GT(rays[1].direction.y, 0.f);
    EXPECT_LT(rays[7].direction.y, 0.f);
    EXPECT_LT(rays[3].direction.x, 0.f);
    // With a 90° field, the top row's centre ray is at sy = (1 − 2·0.5/3)·tan 45° = 2/3.
    const glm::dvec3 expected = glm::normalize(glm::dvec3(0.0, 2.0 / 3.0, -1.0));
    EXPECT_EQ(rays[1].direction, glm::vec3(expected));
    for (const Ray &r : rays) EXPECT_NEAR(glm::length(r.direction), 1.f, 1e-6f);
}

TEST(CastRays, OriginsAreInSceneSpace) {
    CastCamera c = lookDownMinusZ(40.0);
    c.eye = {1e7 + 1.0, 2.0, 3.0};
    c.target = c.eye + glm::dvec3(0.0, 0.0, -1.0);
    const std::vector<Ray> rays = castRays(c, 2, 2, glm::dvec3(1e7, 0.0, 0.0));
    EXPECT_EQ(rays[0].origin, glm::vec3(1.f, 2.f, 3.f)); // subtracted in double, rounded once
}

TEST(CastRays, CameraTextReadsBackToTheSameCamera) {
    CastCamera c;
    c.eye = {0.1, -2.0 / 3.0, 1e-9};
    c.target = {4.0, 5.0, 6.0};
    c.up = {0.0, 0.0, 1.0};
    c.verticalFovDegrees = 33.3;
    const CastCamera back = CastCamera::parse(c.text());
    EXPECT_EQ(back.eye, c.eye);
    EXPECT_EQ(back.target, c.target);
    EXPECT_EQ(back.up, c.up);
    EXPECT_EQ(back.verticalFovDegrees, c.verticalFovDegrees);
}

TEST(CastRays, BadCamerasAreClearErrors) {
    EXPECT_THROW(CastCamera::parse("1,2,3"), Error);
    EXPECT_THROW(CastCamera::parse("0,0,0,0,0,-1,0,1,0,nan"), Error);
    EXPECT_THROW(CastCamera::parse("0,0,0,0,0,-1,0,1,0,x"), Error);
    EXPECT_THROW(CastCamera::parse("0,0,0,0,0,-1,0,1,0,180"), Error);
    EXPECT_THROW(CastCamera::parse("0,0,0,0,0,-1,0,1,0,"), Error);
    try {
        castRays(CastCamera::parse("0,0,0,0,0,0,0,1,0,40"), 4, 4, glm::dvec3(0.0));
        FAIL() << "eye == target accepted";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("same point"), std::string::npos) << e.what();
    }
    EXPECT_THROW(castRays(CastCamera::parse("0,0,0,0,0,-1,0,0,1,40"), 4, 4, glm::dvec3(0.0)), Error);
}

TEST(CastRays, ACastOnAPlaneHitsEveryPixelAtItsKnownDistance) {
    // A square at z = −2, much larger than the view: every ray hits it at t = 2 / −d.z.
    Scene scene;
    TriangleMesh plane;
    plane.positions = {{-100.f, -100.f, -2.f}, {100.f, -100.f, -2.f}, {100.f, 100.f, -2.f}, {-100.f, 100.f, -2.f}};
    plane.indices = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(plane);
    scene.materials.emplace_back();
    const Tracer tracer(scene);
    const std::vector<Ray> rays = castRays(lookDownMinusZ(60.0), 37, 23, scene.worldOrigin);
    double sum = 0.0, expected = 0.0;
    for (const Ray &ray : rays) {
        Hit hit;
        ASSERT_TRUE(tracer.closestHit(ray, {}, hit));
        sum += double(hit.t);
        expected += 2.0 / -double(ray.direction.z);
    }
    EXPECT_NEAR(sum, expected, 1e-6 * expected);
}

} // namespace
} // namespace mvcl::bench
