#include <mvcl/view/Renderer.h>

#include "ImageCompare.h"
#include "TestRender.h"

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace mvcl;

namespace {

using test::TestRender;
using test::nonFinitePixels;

TestRender renderBuiltin(const std::string &name, int width, int height, int spp, int threads,
                         const RayPolicy &policy = {}) {
    const Scene scene = makeBuiltinScene(name);
    const Tracer tracer(scene);
    return test::renderWithPolicy(tracer, Camera::fromDesc(scene.cameras.front()), width, height, spp, threads,
                                  policy);
}

} // namespace

TEST(Renderer, ImageIsIdenticalForAnyThreadCount) {
    const TestRender one = renderBuiltin("cube-in-cube", 96, 72, 4, 1);
    const TestRender two = renderBuiltin("cube-in-cube", 96, 72, 4, 2);
    const TestRender five = renderBuiltin("cube-in-cube", 96, 72, 4, 5);
    EXPECT_EQ(one.image.pixels(), two.image.pixels());
    EXPECT_EQ(one.image.pixels(), five.image.pixels());
    EXPECT_EQ(one.stats.rays.total(), two.stats.rays.total());
}

TEST(Renderer, CountsEveryRayTypeOnTheDefaultScene) {
    const TestRender r = renderBuiltin("cube-in-cube", 80, 60, 1, 0);
    EXPECT_EQ(r.stats.pixels, 80u * 60u);
    EXPECT_GE(r.stats.rays.primary, 80u * 60u);
    EXPECT_GT(r.stats.rays.shadow, 0u);
    EXPECT_GT(r.stats.rays.reflection, 0u);
    EXPECT_GT(r.stats.rays.refraction, 0u);
    EXPECT_EQ(nonFinitePixels(r.image), 0u);
}

TEST(Renderer, SceneWithoutLightsTracesNoShadowRays) {
    Scene scene = makeBuiltinScene("onion");
    scene.lights.clear();
    const Tracer tracer(scene);
    RenderSettings settings;
    settings.width = 32;
    settings.height = 32;
    settings.samplesPerPixel = 1;
    Framebuffer image;
    const RenderStats stats = Renderer(tracer).render(Camera::fromDesc(scene.cameras.front()),
                                                      PolicyMap(32, 32), settings, image);
    EXPECT_EQ(stats.rays.shadow, 0u);
}

TEST(Renderer, RejectsBadSettingsAndMismatchedPolicyMap) {
    const Scene scene = makeBuiltinScene("onion");
    const Tracer tracer(scene);
    RenderSettings settings;
    settings.width = 16;
    settings.height = 16;
    Framebuffer image;
    EXPECT_THROW(Renderer(tracer).render(Camera(), PolicyMap(8, 8), settings, image), Error);
    settings.samplesPerPixel = 0;
    EXPECT_THROW(Renderer(tracer).render(Camera(), PolicyMap(16, 16), settings, image), Error);
}

// The default scene is the regression image of the whole pipeline (loader → BVH → Whitted →
// stratified sampling → sRGB). Regenerate with MVCL_UPDATE_GOLDEN=1 after an intended change.
TEST(Renderer, DefaultSceneMatchesGoldenImage) {
    const std::filesystem::path golden = std::filesystem::path(MVCL_GOLDEN_DIR) / "cube-in-cube.png";
    const TestRender r = renderBuiltin("cube-in-cube", 200, 150, 4, 0);
    if (test::updateGoldenRequested()) {
        writeImage(golden, r.image);
        GTEST_SKIP() << "wrote " << golden;
    }
    ASSERT_TRUE(std::filesystem::exists(golden)) << golden << " is missing";
    const test::ImageDifference diff = test::compareImages(r.image, readImage(golden), 8);
    EXPECT_LT(diff.differingFraction, 0.002) << "max channel delta " << diff.maxChannelDelta;
}

TEST(Renderer, PolicyMapRevealsTheInnerCubeOnlyWhereAsked) {
    // Left half of the image sees only layer 1 (the inner cube); the right half sees everything.
    const Scene scene = makeBuiltinScene("cube-in-cube");
    const Tracer tracer(scene);
    const int w = 120, h = 90;
    PolicyMap map(w, h);
    PixelPolicy inner;
    inner.ray.query(RayType::Primary).layerMask = layerBit(1);
    const uint16_t innerId = map.addPolicy(inner);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w / 2; ++x) map.setPixel(x, y, innerId);
    RenderSettings settings;
    settings.width = w;
    settings.height = h;
    settings.samplesPerPixel = 1;
    Framebuffer image;
    Renderer(tracer).render(Camera::fromDesc(scene.cameras.front()), map, settings, image);

    // The default view looks at the cubes across the image's middle, so both halves show one.
    int reds = 0, blues = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 c = image.at(x, y);
            const bool red = c.r > 2.f * c.b && c.r > 0.05f;
            const bool blue = c.b > 1.5f * c.r && c.b > 0.05f;
            if (x < w / 2) reds += red;
            else blues += blue;
        }
    EXPECT_GT(reds, 50) << "the inner (red) cube shows through on the left";
    EXPECT_GT(blues, 50) << "the outer (blue) cube still covers the right";
}

// Blocks of pixels outside the camera footprint of the tracer's bounds are left untraced (a scene
// without planes, its model small in the image): each of their samples must be what tracing its
// ray gives, with the same counts, as at every other pixel.
TEST(Renderer, UntracedBlocksAroundTheModelEqualTracedRays) {
    Scene scene = makeBuiltinScene("onion");
    scene.planes.clear();
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    const Camera camera = Camera::lookAt({0.5f, 2.f, 9.f}, {0.3f, 1.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    const int width = 70, height = 52; // not whole blocks at the right and bottom edges
    RayPolicy tinted;
    tinted.color.matrix = glm::mat3(0.7f);
    tinted.color.offset = {0.05f, 0.1f, 0.f};
    for (const RayPolicy &policy : {RayPolicy{}, tinted}) {
        const TestRender r = test::renderWithPolicy(tracer, camera, width, height, 1, 2, policy);
        const IntegratorPlan plan = integrator.plan(policy, StageSelection::SkipUnneeded);
        RayCounters expected;
        int background = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                RayCounters own;
                const glm::vec3 value = integrator.radiance(
                    camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, width, height), policy, plan, own);
                ASSERT_EQ(r.image.at(x, y), value) << x << ", " << y;
                expected += own;
                background += own.total() == 1;
            }
        EXPECT_GT(background, width * height / 2); // most blocks lie outside the model
        EXPECT_EQ(r.stats.rays.primary, expected.primary);
        EXPECT_EQ(r.stats.rays.total(), expected.total());
        EXPECT_EQ(r.stats.rays.skippedColorMaps, expected.skippedColorMaps);
    }
}
