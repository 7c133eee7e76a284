// The opacity stage of the integrator: a partly opaque primary hit blends its shading with what
// the ray meets beyond it. Checked against the layer mask on builtin:cube-in-cube (layer 0: the
// outer cube, floor and spheres; layer 1: the inner cube).

#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>
#include <mvcl/view/Camera.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace mvcl {
namespace {

struct OpacityScene {
    Scene scene = makeBuiltinScene("cube-in-cube");
    Tracer tracer{scene};
    WhittedIntegrator integrator{tracer};
    Camera camera = Camera::fromDesc(scene.cameras.front());

    glm::vec3 radiance(int x, int y, const RayPolicy &policy) const {
        RayCounters counters;
        return integrator.radiance(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, 64, 48), policy, counters);
    }
};

RayPolicy outerOpacity(float opacity, float edges = 0.f) {
    RayPolicy policy;
    policy.shading.layerOpacity[0] = opacity;
    policy.shading.edgeOpacity = edges;
    return policy;
}

TEST(OpacityStage, OpaqueLayersRenderExactlyAsWithoutTheStage) {
    const OpacityScene s;
    const RayPolicy opaque = outerOpacity(1.f);
    for (int y = 0; y < 48; y += 3)
        for (int x = 0; x < 64; x += 3) EXPECT_EQ(s.radiance(x, y, opaque), s.radiance(x, y, RayPolicy{}));
    EXPECT_EQ(s.integrator.plan(opaque, StageSelection::SkipUnneeded).translucentLayers, 0u);
}

TEST(OpacityStage, APartlyOpaqueSurfaceBlendsItsShadingWithWhatLiesBehind) {
    // One surface in front of another: a plane (layer 0) between the camera and a sphere
    // (layer 1), so the onward ray crosses exactly one translucent surface.
    Scene scene;
    scene.materials.resize(1);
    scene.spheres.push_back({"ball", {0.f, 0.f, 0.f}, 1.f, 0, 1});
    scene.planes.push_back({"veil", {0.f, 0.f, 1.f}, 2.f, 0, 0});
    scene.lights.push_back({"sun", LightType::Directional, {}, glm::normalize(glm::vec3(-0.3f, -0.5f, -1.f))});
    scene.layers.ensure(0);
    scene.layers.ensure(1);
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    const Camera camera = Camera::lookAt({0.f, 0.f, 6.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    RayPolicy hidden; // what lies behind the veil
    hidden.query(RayType::Primary).layerMask = layerBit(1);
    for (const float opacity : {0.f, 0.3f, 0.5f, 0.9f}) {
        const RayPolicy translucent = outerOpacity(opacity);
        for (int y = 0; y < 24; y += 3)
            for (int x = 0; x < 32; x += 3) {
                RayCounters counters;
                const Ray ray = camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, 32, 24);
                const glm::vec3 front = integrator.radiance(ray, RayPolicy{}, counters);
                const glm::vec3 behind = integrator.radiance(ray, hidden, counters);
                const glm::vec3 blended = integrator.radiance(ray, translucent, counters);
                EXPECT_LT(glm::length(blended - (opacity * front + (1.f - opacity) * behind)), 1e-5f)
                    << "opacity " << opacity << " at " << x << "," << y;
            }
    }
}

TEST(OpacityStage, PeelingShowsTheKthSurfaceAlongThePrimaryRay) {
    // cube-in-cube from its camera: a ray through the centre meets the outer cube's front wall,
    // the inner cube's front and back, the outer cube's back wall. Peeling one surface equals
    // hiding the outer cube where it is the first hit and the inner cube lies behind it.
    const OpacityScene s;
    RayPolicy peelOne;
    peelOne.shading.peelSurfaces = 1;
    RayPolicy withoutOuter;
    withoutOuter.query(RayType::Primary).layerMask = ~layerBit(0);
    const glm::vec3 centre = s.radiance(32, 24, peelOne);
    EXPECT_LT(glm::length(centre - s.radiance(32, 24, withoutOuter)), 1e-4f);
    EXPECT_NE(centre, s.radiance(32, 24, RayPolicy{}));
    RayPolicy peelMany;
    peelMany.shading.peelSurfaces = 40; // more surfaces than any ray meets: the background
    EXPECT_EQ(s.radiance(32, 24, peelMany), s.scene.background);
    RayPolicy none;
    none.shading.peelSurfaces = 0;
    EXPECT_EQ(s.radiance(32, 24, none), s.radiance(32, 24, RayPolicy{}));
}

TEST(OpacityStage, PeelingPassesOnlyItsLayers) {
    // The centre ray's first surface is the outer cube (layer 0): peeling only layer 1 leaves it
    // in place; peeling layers 0 and 1 is the same as peeling every layer.
    const OpacityScene s;
    RayPolicy innerOnly;
    innerOnly.shading.peelSurfaces = 1;
    innerOnly.shading.peelLayers = layerBit(1);
    EXPECT_EQ(s.radiance(32, 24, innerOnly), s.radiance(32, 24, RayPolicy{}));
    RayPolicy both = innerOnly, all = innerOnly;
    both.shading.peelLayers = layerBit(0) | layerBit(1);
    all.shading.peelLayers = kAllLayers;
    EXPECT_EQ(s.radiance(32, 24, both), s.radiance(32, 24, all));
    EXPECT_NE(s.radiance(32, 24, both), s.radiance(32, 24, RayPolicy{}));
}

TEST(OpacityStage, EdgeOpacityMakesGrazingSurfacesMoreOpaque) {
    const OpacityScene s;
    const RayPolicy plain = outerOpacity(0.f, 0.f), edged = outerOpacity(0.f, 1.f);
    int differing = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            if (s.radiance(x, y, plain) != s.radiance(x, y, edged)) ++differing;
    EXPECT_GT(differing, 100) << "with edges = 1 every surface not seen head-on keeps some opacity";
}

TEST(OpacityStage, ThePrimaryRaysConstraintsHoldBeyondATranslucentHit) {
    // A layer lens's distance (tMin from the camera) and mask still apply to the onward ray.
    const OpacityScene s;
    RayPolicy through = outerOpacity(0.f);
    through.query(RayType::Primary).layerMask = layerBit(0); // nothing but layer 0 to see
    RayPolicy hiddenAll;
    hiddenAll.query(RayType::Primary).layerMask = 0;
    for (int y = 4; y < 48; y += 8)
        for (int x = 4; x < 64; x += 8) EXPECT_EQ(s.radiance(x, y, through), s.radiance(x, y, hiddenAll)) << x << "," << y;
}

} // namespace
} // namespace mvcl
