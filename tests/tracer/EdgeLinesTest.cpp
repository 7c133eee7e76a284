// Edge lines over primary hits: triangle edges (wireframe) and outlines (silhouettes, mesh
// boundaries, creases) found by probe rays half a line width around the pixel's ray.

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>
#include <mvcl/view/Camera.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>

namespace mvcl {
namespace {

constexpr int kSize = 64;
const glm::vec3 kLineColor{1.f, 0.f, 1.f};

RayPolicy lines(EdgeLineMode mode, float creaseDegrees = 40.f) {
    RayPolicy policy;
    policy.shading.edges = {mode, kLineColor, 2.f, creaseDegrees};
    return policy;
}

struct View {
    Scene scene;
    Camera camera = Camera::lookAt({0.f, 0.f, 6.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);

    glm::vec3 pixel(int x, int y, const RayPolicy &policy) const {
        const Tracer tracer(scene);
        const WhittedIntegrator integrator(tracer);
        RayCounters counters;
        return integrator.radiance(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, kSize, kSize), policy,
                                   counters);
    }
};

Scene withLight(Scene scene) {
    scene.materials.resize(1);
    scene.layers.ensure(0);
    scene.lights.push_back({"sun", LightType::Directional, {}, glm::normalize(glm::vec3(-0.3f, -0.4f, -1.f))});
    return scene;
}

TEST(EdgeLines, TrianglesDrawTheWireframeAndLeaveTriangleInteriorsAlone) {
    // A square of two triangles facing the camera, its diagonal running corner to corner.
    Scene scene;
    TriangleMesh quad;
    quad.positions = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
    quad.indices = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(quad);
    const View view{withLight(scene)};
    const RayPolicy wire = lines(EdgeLineMode::Triangles);
    // The centre of this pixel lies on the shared diagonal: the line colour, fully.
    EXPECT_EQ(view.pixel(kSize / 2 - 1, kSize / 2, wire), kLineColor);
    // Pixels well inside either triangle are shaded as without lines.
    for (const auto &[x, y] : {std::array{kSize / 2 + 8, kSize / 2 + 3}, std::array{kSize / 2 - 8, kSize / 2 - 3}})
        EXPECT_EQ(view.pixel(x, y, wire), view.pixel(x, y, RayPolicy{}));
}

TEST(EdgeLines, OutlinesFollowTheSilhouetteOnBothSides) {
    Scene scene;
    scene.spheres.push_back({"ball", {0.f, 0.f, 0.f}, 1.f, 0, 0});
    const View view{withLight(scene)};
    const RayPolicy outlines = lines(EdgeLineMode::Outlines);
    // Along the middle row: the ball covers the pixels whose ray passes within radius 1.
    int linePixels = 0, insideLines = 0, outsideLines = 0;
    const Tracer tracer(view.scene);
    for (int x = 0; x < kSize; ++x) {
        const glm::vec3 withLines = view.pixel(x, kSize / 2, outlines), without = view.pixel(x, kSize / 2, RayPolicy{});
        Hit hit;
        const bool onBall = tracer.closestHit(view.camera.generateRay(float(x) + 0.5f, kSize / 2 + 0.5f, kSize, kSize),
                                              RayQuery{}, hit);
        if (withLines == without) continue;
        EXPECT_EQ(withLines, kLineColor) << "x " << x;
        ++linePixels;
        (onBall ? insideLines : outsideLines)++;
    }
    // Two crossings, a 2-pixel line each, straddling the silhouette.
    EXPECT_GE(linePixels, 2);
    EXPECT_LE(linePixels, 6);
    EXPECT_GE(insideLines, 2);
    EXPECT_GE(outsideLines, 0);
    // The ball's middle is smooth: no line there.
    EXPECT_EQ(view.pixel(kSize / 2, kSize / 2, outlines), view.pixel(kSize / 2, kSize / 2, RayPolicy{}));
}

TEST(EdgeLines, CreasesSharperThanTheAngleDrawALine) {
    // A box corner seen from its diagonal: three faces meeting at 90°, flat-shaded.
    Scene scene;
    TriangleMesh corner;
    const std::array<glm::vec3, 3> axes{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
    for (int face = 0; face < 3; ++face) {
        const glm::vec3 u = axes[size_t(face)], v = axes[size_t((face + 1) % 3)];
        const uint32_t base = uint32_t(corner.positions.size());
        corner.positions.insert(corner.positions.end(), {glm::vec3(0.f), 2.f * u, 2.f * (u + v), 2.f * v});
        corner.indices.push_back({base, base + 1, base + 2});
        corner.indices.push_back({base, base + 2, base + 3});
    }
    scene.meshes.push_back(corner);
    View view{withLight(scene)};
    view.camera = Camera::lookAt({5.f, 5.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f);
    // The edge between the x-y and y-z faces runs from the image centre straight up to the
    // silhouette (row 5); the rows between see only the crease.
    int sharp = 0, blunt = 0;
    for (int y = 8; y < kSize / 2 - 4; ++y) {
        sharp += view.pixel(kSize / 2, y, lines(EdgeLineMode::Outlines, 40.f)) == kLineColor;
        blunt += view.pixel(kSize / 2, y, lines(EdgeLineMode::Outlines, 120.f)) == kLineColor;
    }
    EXPECT_EQ(sharp, kSize / 2 - 12);
    EXPECT_EQ(blunt, 0);
}

} // namespace
} // namespace mvcl
