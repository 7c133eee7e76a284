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
