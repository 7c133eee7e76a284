// The false-colour stage: primary hits show depth, normal, layer or mesh instead of lighting.

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace mvcl {
namespace {

/// Two balls on the z axis in front of a camera at z = 10 looking down −z: the near one (layer
/// 0) at distance 4, the far one (layer 1) at distance 14, off to the side so both are seen.
struct Balls {
    Scene scene = [] {
        Scene s;
        s.materials.resize(1);
        s.spheres.push_back({"near", {-2.f, 0.f, 5.f}, 1.f, 0, 0});
        s.spheres.push_back({"far", {2.f, 0.f, -5.f}, 1.f, 0, 1});
        s.layers.ensure(0);
        s.layers.ensure(1);
        s.lights.push_back({"sun", LightType::Directional, {}, {0.f, 0.f, -1.f}});
        return s;
    }();
    Tracer tracer{scene};
    WhittedIntegrator integrator{tracer};

    /// The ray from the camera to the point of `sphere` nearest the camera.
    glm::vec3 colorOf(int sphere, const RayPolicy &policy) const {
        const glm::vec3 eye{0.f, 0.f, 10.f};
        const glm::vec3 front = scene.spheres[size_t(sphere)].center + glm::vec3(0.f, 0.f, 1.f);
        RayCounters counters;
        return integrator.radiance({eye, glm::normalize(front - eye)}, policy, counters);
    }
};

RayPolicy falseColor(FalseColorMode mode, float depthNear = 0.f, float depthFar = 20.f) {
    RayPolicy policy;
    policy.shading.falseColor = {mode, depthNear, depthFar};
    return policy;
}

TEST(FalseColor, DepthRisesFromDarkBlueToYellowOverTheRange) {
    const Balls b;
    const glm::vec3 nearBall = b.colorOf(0, falseColor(FalseColorMode::Depth));
    const glm::vec3 farBall = b.colorOf(1, falseColor(FalseColorMode::Depth));
    // The ramp's green and red rise with distance, its blue falls at the yellow end.
    EXPECT_LT(nearBall.g, farBall.g);
    EXPECT_LT(nearBall.r, farBall.r);
    EXPECT_GT(nearBall.b, farBall.b);
    // Distances outside the range clamp to its ends: both balls nearer than 20 → ramp start.
    EXPECT_EQ(b.colorOf(0, falseColor(FalseColorMode::Depth, 30.f, 40.f)),
              b.colorOf(1, falseColor(FalseColorMode::Depth, 30.f, 40.f)));
    EXPECT_EQ(b.colorOf(0, falseColor(FalseColorMode::Depth, 0.f, 1.f)),
              b.colorOf(1, falseColor(FalseColorMode::Depth, 0.f, 1.f)));
    EXPECT_NE(b.colorOf(0, falseColor(FalseColorMode::Depth, 0.f, 1.f)),
              b.colorOf(0, falseColor(FalseColorMode::Depth, 30.f, 40.f)));
}

TEST(FalseColor, NormalsShowAsRgbOfTheirWorldAxes) {
    const Balls b;
    // The ray meets each ball's front point, where the normal is close to +z: blue dominates,
    // red and green sit near the middle grey (0.5 displayed ≈ 0.214 linear).
    const glm::vec3 c = b.colorOf(0, falseColor(FalseColorMode::Normal));
    EXPECT_GT(c.b, 0.9f);
    EXPECT_NEAR(c.g, 0.214f, 0.03f);
    EXPECT_NEAR(c.r, 0.214f, 0.03f);
}

TEST(FalseColor, LayersAndMeshesGetColoursOfTheirOwnWhateverTheLighting) {
    Balls b;
    const glm::vec3 layer0 = b.colorOf(0, falseColor(FalseColorMode::Layer));
    const glm::vec3 layer1 = b.colorOf(1, falseColor(FalseColorMode::Layer));
    EXPECT_NE(layer0, layer1);
    EXPECT_NE(b.colorOf(0, falseColor(FalseColorMode::Mesh)), b.colorOf(1, falseColor(FalseColorMode::Mesh)));
    const glm::vec3 lit = b.colorOf(0, RayPolicy{});
    // Lighting plays no part: a tenfold brighter sun leaves false colours as they are.
    b.scene.lights.front().intensity = glm::vec3(10.f);
    const Tracer brighter(b.scene);
    const WhittedIntegrator integrator(brighter);
    RayCounters counters;
    const glm::vec3 eye{0.f, 0.f, 10.f};
    const Ray toNear{eye, glm::normalize(glm::vec3(-2.f, 0.f, 6.f) - eye)};
    EXPECT_EQ(integrator.radiance(toNear, falseColor(FalseColorMode::Layer), counters), layer0);
    EXPECT_NE(integrator.radiance(toNear, RayPolicy{}, counters), lit);
}

TEST(FalseColor, OffLeavesTheImageAsItWas) {
    const Balls b;
    EXPECT_EQ(b.colorOf(0, falseColor(FalseColorMode::Off)), b.colorOf(0, RayPolicy{}));
}

} // namespace
} // namespace mvcl
