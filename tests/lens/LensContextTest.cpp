// LensContext: world, view and scene space conversions, and what counts as the same scene or view.

#include <mvcl/lens/LensContext.h>

#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/Scene.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace mvcl {
namespace {

bool near(const glm::vec3 &a, const glm::vec3 &b, float tolerance = 1e-5f) { return glm::length(a - b) <= tolerance; }

LensContext farAwayContext() {
    LensContext context;
    context.worldOrigin = {1.0e6, -2.5e5, 3.0};
    context.camera.eye = {0.f, 0.f, 10.f};
    context.camera.target = {0.f, 0.f, 0.f};
    context.camera.up = {0.f, 1.f, 0.f};
    return context;
}

TEST(LensContext, BoundsSpaceIsFractionsOfTheSceneBoundsAndConvertsBack) {
    LensContext context = farAwayContext();
    context.sceneBounds = Bounds3f{{-2.f, 0.f, 1.f}, {2.f, 8.f, 2.f}};
    EXPECT_EQ(context.scenePoint({0.5, 0.25, 1.0}, PropertySpace::Bounds), glm::vec3(0.f, 2.f, 2.f));
    EXPECT_DOUBLE_EQ(context.sceneLength(0.5, PropertySpace::Bounds), 4.0) << "of the largest side";
    // A normal in bounds space turns with the inverse stretch: the plane through (0.5, 0.5, 0)
    // with bounds normal (1, 1, 0) passes through (1, 0, ·) and (0, 1, ·) in bounds space.
    const glm::vec3 n = context.sceneNormal({1.0, 1.0, 0.0}, PropertySpace::Bounds);
    const glm::vec3 a = context.scenePoint({1.0, 0.0, 0.0}, PropertySpace::Bounds);
    const glm::vec3 b = context.scenePoint({0.0, 1.0, 0.0}, PropertySpace::Bounds);
    EXPECT_NEAR(glm::dot(n, a - b), 0.f, 1e-6f);
    for (PropertySpace space : {PropertySpace::World, PropertySpace::Bounds, PropertySpace::View}) {
        const glm::dvec3 p{0.3, -0.7, 1.9};
        EXPECT_LT(glm::length(context.propertyPoint(context.scenePointInDouble(p, space), space) - p), 1e-5);
        EXPECT_LT(glm::length(context.propertyVector(glm::dvec3(context.sceneVector(p, space)), space) - p), 1e-5);
        EXPECT_NEAR(context.propertyLength(context.sceneLength(0.7, space), space), 0.7, 1e-12);
    }
    const Box3d box{{0.25, 0.5, 0.0}, {0.75, 1.0, 0.5}};
    const LensContext::OrientedBox oriented = context.sceneOrientedBox(box, glm::dmat4(1.0), PropertySpace::Bounds);
    EXPECT_EQ(oriented.center, glm::dvec3(0.0, 6.0, 1.25));
    EXPECT_EQ(oriented.halfExtent, glm::dvec3(1.0, 2.0, 0.25));
    EXPECT_EQ(context.propertyBox(oriented.center - oriented.halfExtent, oriented.center + oriented.halfExtent,
                                  PropertySpace::Bounds),
              box);
}

TEST(LensContext, WorldPointsAreSceneSpacePlusTheWorldOrigin) {
    const LensContext context = farAwayContext();
    const glm::dvec3 world{1.0e6 + 1.25, -2.5e5 - 0.5, 5.0};
    EXPECT_EQ(context.sceneFromWorldPoint(world), glm::vec3(1.25f, -0.5f, 2.f)) << "exact: subtracted in double";
    EXPECT_EQ(context.worldFromScenePoint({1.25f, -0.5f, 2.f}), world);
    EXPECT_EQ(context.scenePoint(world, PropertySpace::World), glm::vec3(1.25f, -0.5f, 2.f));
    EXPECT_EQ(context.sceneVector({0.0, 0.0, 1.0}, PropertySpace::World), glm::vec3(0.f, 0.f, 1.f));
}

TEST(LensContext, ViewSpaceIsTheCameraFrame) {
    LensContext context = farAwayContext();
    // From +x looking at the origin: view x (right) is scene −z, view −z (forward) is scene −x.
    context.camera.eye = {10.f, 0.f, 0.f};
    EXPECT_TRUE(near(context.scenePoint({0.0, 0.0, -4.0}, PropertySpace::View), {6.f, 0.f, 0.f}));
    EXPECT_TRUE(near(context.sceneVector({1.0, 0.0, 0.0}, PropertySpace::View), {0.f, 0.f, -1.f}));
    EXPECT_TRUE(near(context.sceneVector({0.0, 1.0, 0.0}, PropertySpace::View), {0.f, 1.f, 0.f}));
    const Bounds3f box = context.sceneBox({{-1.0, -1.0, -5.0}, {1.0, 1.0, -3.0}}, PropertySpace::View);
    EXPECT_TRUE(near(box.min, {5.f, -1.f, -1.f}));
    EXPECT_TRUE(near(box.max, {7.f, 1.f, 1.f}));
}

TEST(LensContext, TransformsActOnSceneSpaceLikeTheyDoInTheirSpace) {
    const LensContext context = farAwayContext();
    glm::dmat4 shift(1.0); // +2 along world x
    shift[3] = glm::dvec4(2.0, 0.0, 0.0, 1.0);
    const glm::mat4 scene = context.sceneTransform(shift, PropertySpace::World);
    const glm::vec3 p(1.f, 2.f, 3.f);
    EXPECT_TRUE(near(glm::vec3(scene * glm::vec4(p, 1.f)), p + glm::vec3(2.f, 0.f, 0.f)));
    glm::dmat4 scale(2.0); // doubles distances from the world origin
    scale[3][3] = 1.0;
    const glm::mat4 scaled = context.sceneTransform(scale, PropertySpace::World);
    const glm::dvec3 world = context.worldFromScenePoint(p);
    EXPECT_TRUE(near(glm::vec3(scaled * glm::vec4(p, 1.f)), context.sceneFromWorldPoint(2.0 * world), 1.f))
        << "scene points far from the world origin move far";
}

TEST(LensContext, SameSceneAndSameViewCompareWhatALensMayRead) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const LensContext a = LensContext::forScene(scene);
    LensContext b = a;
    EXPECT_TRUE(a.sameScene(b));
    EXPECT_TRUE(a.sameView(b));
    b.camera.eye.x += 1.f;
    EXPECT_TRUE(a.sameScene(b));
    EXPECT_FALSE(a.sameView(b));
    b = a;
    b.imageWidth = 640;
    EXPECT_FALSE(a.sameView(b));
    b = a;
    b.worldOrigin.y = 1.0;
    EXPECT_FALSE(a.sameScene(b));
    b = a;
    b.layers.ensure(7);
    EXPECT_FALSE(a.sameScene(b));
    EXPECT_FALSE(a.sceneBounds.isEmpty());
    EXPECT_EQ(a.sceneBounds.min, scene.bounds().min);
}

} // namespace
} // namespace mvcl
