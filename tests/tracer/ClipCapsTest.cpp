// Clip caps: where a capped clip volume cuts through a closed mesh, a primary ray shows the cut
// face as a solid surface. Checked against geometry that really is cut: a box cut at z = 0
// with caps renders as the box truncated at z = 0.

#include <mvcl/model/MeshClosure.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>
#include <mvcl/view/Camera.h>

#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <utility>

namespace mvcl {
namespace {

constexpr int kSize = 48;

/// A closed box of `material` in `layer`.
TriangleMesh box(const glm::vec3 &lo, const glm::vec3 &hi, uint32_t material, int layer) {
    TriangleMesh mesh = test::splitFaceBox(lo, hi);
    mesh.name = "box";
    mesh.material = material;
    mesh.layer = layer;
    mesh.layerSource = LayerSource::Builtin;
    return mesh;
}

/// `meshes` lit by a sun travelling along `sunDirection`.
Scene sceneOf(std::vector<TriangleMesh> meshes, const glm::vec3 &sunDirection = {-0.4f, -0.5f, -1.f}) {
    Scene scene;
    Material blue, red;
    blue.diffuse = {0.2f, 0.3f, 0.8f};
    red.diffuse = {0.8f, 0.2f, 0.1f};
    scene.materials = {blue, red};
    scene.meshes = std::move(meshes);
    for (const TriangleMesh &mesh : scene.meshes) scene.layers.ensure(mesh.layer);
    scene.lights.push_back({"sun", LightType::Directional, {}, glm::normalize(sunDirection)});
    recordMeshClosure(scene);
    return scene;
}

const Camera kCamera = Camera::lookAt({3.f, 2.5f, 4.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);

/// The image of `scene` under `policy`, one ray per pixel centre.
std::vector<glm::vec3> render(const Scene &scene, const RayPolicy &policy, const Camera &camera = kCamera) {
    const Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    std::vector<glm::vec3> image;
    RayCounters counters;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            image.push_back(integrator.radiance(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, kSize, kSize),
                                                policy, counters));
    return image;
}

/// Cuts z ≥ 0 away from primary rays, with caps of `style`.
RayPolicy cutUpperHalf(ClipVolume::CapStyle style) {
    ClipVolume upper = ClipVolume::halfSpace({0.f, 0.f, 1.f}, 0.f, ClipVolume::Keep::Outside);
    upper.setCapStyle(style);
    RayPolicy policy;
    policy.query(RayType::Primary).addClip(upper);
    return policy;
}

/// Pixels where the two images differ by more than `tolerance` in some channel.
int differingPixels(const std::vector<glm::vec3> &a, const std::vector<glm::vec3> &b, float tolerance = 1e-4f) {
    int count = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (glm::any(glm::greaterThan(glm::abs(a[i] - b[i]), glm::vec3(tolerance)))) ++count;
    return count;
}

TEST(ClipCaps, ACappedCutRendersAsTheTrulyCutSolid) {
    const Scene whole = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0)});
    const Scene truncated = sceneOf({box({-1, -1, -1}, {1, 1, 0}, 0, 0)});
    const std::vector<glm::vec3> expected = render(truncated, RayPolicy{});
    const std::vector<glm::vec3> capped = render(whole, cutUpperHalf(ClipVolume::CapStyle::Solid));
    // Only pixels on the rim of the cut may differ (the cap and the truncated box's top face
    // meet the side faces at slightly different rounding).
    EXPECT_LE(differingPixels(capped, expected), kSize / 2);
    // Without caps the ray sees the inside of the shell instead: many pixels differ.
    const std::vector<glm::vec3> hollow = render(whole, cutUpperHalf(ClipVolume::CapStyle::None));
    EXPECT_GT(differingPixels(hollow, expected), kSize * kSize / 20);
}

TEST(ClipCaps, HatchedCapsStripeTheCutFaceOnly) {
    const Scene whole = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0)});
    const std::vector<glm::vec3> solid = render(whole, cutUpperHalf(ClipVolume::CapStyle::Solid));
    const std::vector<glm::vec3> hatched = render(whole, cutUpperHalf(ClipVolume::CapStyle::Hatched));
    const std::vector<glm::vec3> hollow = render(whole, cutUpperHalf(ClipVolume::CapStyle::None));
    int darker = 0;
    for (size_t i = 0; i < solid.size(); ++i) {
        if (hatched[i] == solid[i]) continue;
        // A stripe darkens a cap pixel: a pixel where caps and no caps agree is no cap pixel.
        EXPECT_NE(solid[i], hollow[i]) << "pixel " << i;
        EXPECT_LT(hatched[i].r + hatched[i].g + hatched[i].b, solid[i].r + solid[i].g + solid[i].b);
        ++darker;
    }
    EXPECT_GT(darker, 20);
}

TEST(ClipCaps, NestedSolidsShowTheInnermostMaterialOnTheCut) {
    // A red cube inside a blue one, both cut at z = 0: inside the red cube's section the cap is
    // red, lit as the truncated red cube alone would be (nothing above the cut casts a shadow).
    const Scene nested = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0), box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 1, 1)});
    const Scene innerAlone = sceneOf({box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.f}, 1, 1)});
    const std::vector<glm::vec3> capped = render(nested, cutUpperHalf(ClipVolume::CapStyle::Solid));
    const std::vector<glm::vec3> inner = render(innerAlone, RayPolicy{});
    const Tracer innerTracer(innerAlone);
    int innerCapPixels = 0, mismatches = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            Hit hit;
            const Ray ray = kCamera.generateRay(float(x) + 0.5f, float(y) + 0.5f, kSize, kSize);
            // Pixels that see the truncated inner cube's top face, away from its rim.
            if (!innerTracer.closestHit(ray, RayQuery{}, hit) || hit.primitive != 2) continue;
            const SurfaceInteraction si = innerTracer.interaction(ray, hit);
            if (std::abs(si.position.x) > 0.45f || std::abs(si.position.y) > 0.45f) continue;
            ++innerCapPixels;
            const size_t i = size_t(y * kSize + x);
            if (glm::any(glm::greaterThan(glm::abs(capped[i] - inner[i]), glm::vec3(1e-4f)))) ++mismatches;
        }
    EXPECT_GT(innerCapPixels, 20);
    EXPECT_EQ(mismatches, 0);
}

TEST(ClipCaps, ACutThatSparesALayerNeitherCutsNorCapsIt) {
    // A red cube (layer 1) inside a blue one (layer 0), cut at z = 0 on layer 1 only: the blue
    // cube stays whole, so the image is the uncut scene.
    const Scene nested = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0), box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 1, 1)});
    RayPolicy innerOnly = cutUpperHalf(ClipVolume::CapStyle::Solid);
    ClipVolume cut = innerOnly.query(RayType::Primary).clip(0);
    cut.setLayerMask(layerBit(1));
    innerOnly.query(RayType::Primary).clearClips();
    innerOnly.query(RayType::Primary).addClip(cut);
    EXPECT_EQ(differingPixels(render(nested, innerOnly), render(nested, RayPolicy{})), 0);
    // Cutting only the blue cube opens it onto the whole red cube (uncut, no red cap): the
    // same as the blue cube cut away alone with the red one standing.
    cut.setLayerMask(layerBit(0));
    RayPolicy outerOnly; // shadows too: the truncated scene casts none from above the cut
    outerOnly.query(RayType::Primary).addClip(cut);
    outerOnly.query(RayType::Shadow).addClip(cut);
    const Scene redAloneInCut = sceneOf({box({-1, -1, -1}, {1, 1, 0}, 0, 0), box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 1, 1)});
    const std::vector<glm::vec3> spared = render(nested, outerOnly);
    EXPECT_LE(differingPixels(spared, render(redAloneInCut, RayPolicy{})), kSize / 2) << "only the rim of the cut";
    EXPECT_GT(differingPixels(spared, render(nested, cutUpperHalf(ClipVolume::CapStyle::Solid))), kSize * kSize / 50)
        << "the red cube is not capped at z = 0";
}

TEST(ClipCaps, ATurnedBoxCapsAlongItsTurnedFaces) {
    // A box cut by a box turned 90° about z is the same cut as the unturned box with x and y
    // swapped: both images agree.
    const Scene whole = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0)});
    const auto cutBy = [](const ClipVolume &volume) {
        ClipVolume capped = volume;
        capped.setCapStyle(ClipVolume::CapStyle::Solid);
        RayPolicy policy;
        policy.query(RayType::Primary).addClip(capped);
        return policy;
    };
    const glm::vec3 center(0.5f, 0.5f, 0.5f);
    const ClipVolume aligned = ClipVolume::box(center - glm::vec3(0.3f, 0.8f, 0.8f), center + glm::vec3(0.3f, 0.8f, 0.8f),
                                               ClipVolume::Keep::Outside);
    const glm::mat3 quarterTurn({0.f, 1.f, 0.f}, {-1.f, 0.f, 0.f}, {0.f, 0.f, 1.f});
    const ClipVolume turned =
        ClipVolume::orientedBox(center, glm::vec3(0.8f, 0.3f, 0.8f), quarterTurn, ClipVolume::Keep::Outside);
    ASSERT_TRUE(turned.isOriented());
    const std::vector<glm::vec3> a = render(whole, cutBy(aligned)), b = render(whole, cutBy(turned));
    EXPECT_LE(differingPixels(a, b, 1e-3f), kSize / 4);
    EXPECT_GT(differingPixels(a, render(whole, RayPolicy{})), kSize * kSize / 50) << "it does cut";
}

TEST(ClipCaps, ASolidInsideTheCutSolidStaysHiddenBehindTheCap) {
    // A red box wholly below the cut, inside the blue one: a cut solid hides what it encloses,
    // so the image is the truncated blue box alone.
    const Scene nested = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0), box({-0.3f, -0.3f, -0.8f}, {0.3f, 0.3f, -0.5f}, 1, 1)});
    const Scene truncated = sceneOf({box({-1, -1, -1}, {1, 1, 0}, 0, 0)});
    EXPECT_LE(differingPixels(render(nested, cutUpperHalf(ClipVolume::CapStyle::Solid)), render(truncated, RayPolicy{})),
              kSize / 2);
    // Without caps the red box shows through the opening.
    EXPECT_GT(differingPixels(render(nested, cutUpperHalf(ClipVolume::CapStyle::None)), render(truncated, RayPolicy{})),
              kSize * kSize / 20);
}

TEST(ClipCaps, ASlabThroughASolidRendersAsTheSlabItself) {
    // Keep only −0.2 ≤ z ≤ 0.2: many rays meet no kept surface at all (they enter the slab
    // through its top and leave it through its bottom inside the box), yet see the top cap.
    const Scene whole = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0)});
    const Scene slab = sceneOf({box({-1, -1, -0.2f}, {1, 1, 0.2f}, 0, 0)});
    RayPolicy capped;
    for (const auto &[normal, offset] : {std::pair{glm::vec3(0, 0, 1), 0.2f}, std::pair{glm::vec3(0, 0, -1), 0.2f}}) {
        ClipVolume side = ClipVolume::halfSpace(normal, offset, ClipVolume::Keep::Outside);
        side.setCapStyle(ClipVolume::CapStyle::Solid);
        capped.query(RayType::Primary).addClip(side);
    }
    EXPECT_LE(differingPixels(render(whole, capped), render(slab, RayPolicy{})), kSize / 2);
    RayPolicy hollow = capped;
    hollow.query(RayType::Primary).clearClips();
    for (const ClipVolume &side : capped.query(RayType::Primary).clips()) {
        ClipVolume uncapped = side;
        uncapped.setCapStyle(ClipVolume::CapStyle::None);
        hollow.query(RayType::Primary).addClip(uncapped);
    }
    EXPECT_GT(differingPixels(render(whole, hollow), render(slab, RayPolicy{})), kSize * kSize / 20);
}

TEST(ClipCaps, OpenMeshesAndUncappedVolumesShowTheHollowInside) {
    Scene open = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0)});
    open.meshes.front().closure = MeshClosure::Open;
    EXPECT_EQ(render(open, cutUpperHalf(ClipVolume::CapStyle::Solid)),
              render(open, cutUpperHalf(ClipVolume::CapStyle::None)));
}

TEST(ClipCaps, AKeptInsideVolumeCapsWhereTheRayEntersIt) {
    // Keep only a ball around a corner of the box, seen from the opposite corner: rays pass the
    // near faces (outside the ball, removed), enter the ball inside the box and would see the
    // far walls' inside; with caps they see the ball's surface instead.
    // The sun shines from behind that camera, so that the cap and the walls are lit differently.
    const Scene whole = sceneOf({box({-1, -1, -1}, {1, 1, 1}, 0, 0)}, {0.4f, 0.5f, 1.f});
    ClipVolume ball = ClipVolume::sphere({1.f, 1.f, 1.f}, 1.2f, ClipVolume::Keep::Inside);
    RayPolicy hollow;
    hollow.query(RayType::Primary).addClip(ball);
    ball.setCapStyle(ClipVolume::CapStyle::Solid);
    RayPolicy capped;
    capped.query(RayType::Primary).addClip(ball);
    const Camera behind = Camera::lookAt({-3.f, -2.5f, -4.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    const std::vector<glm::vec3> withCaps = render(whole, capped, behind), without = render(whole, hollow, behind);
    EXPECT_GT(differingPixels(withCaps, without), 20);
    // What is not cap is the same: the kept corner's outer faces.
    EXPECT_LT(differingPixels(withCaps, without), kSize * kSize / 2);
}

} // namespace
} // namespace mvcl
