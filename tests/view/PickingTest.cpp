// Picking through the lens: the pick of a pixel is what its first sample sees under the
// pixel's composed policy, with the names, distance and world position a viewer shows.

#include <mvcl/view/Picking.h>

#include "PluginLens.h"
#include "model/GltfTestWriter.h"

#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/PixelProbe.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <filesystem>

using namespace mvcl;
using test::pluginLens;

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;

LensStack stackOf(std::initializer_list<std::shared_ptr<Lens>> lenses) {
    LensStack stack;
    for (const auto &lens : lenses) stack.add(lens);
    return stack;
}

void expectUnit(const glm::vec3 &v) { EXPECT_NEAR(glm::length(v), 1.f, 1e-5f); }

} // namespace

TEST(Picking, LayerLensPixelPicksTheInnerCubeThatOutsideTheLensPicksTheOuter) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    // The default camera looks at a point inside the inner cube: the centre pixel crosses both.
    const int x = kWidth / 2, y = kHeight / 2;
    const LensRegion overCentre = LensRegion::ellipse({0.5f, 0.5f}, {0.2f, 0.25f});
    const LensRegion inTheCorner = LensRegion::ellipse({0.1f, 0.1f}, {0.15f, 0.15f});

    const PickResult inside =
        pick(tracer, camera, stackOf({pluginLens("layer", overCentre)}).compose({}, kWidth, kHeight), x, y);
    const PickResult outside =
        pick(tracer, camera, stackOf({pluginLens("layer", inTheCorner)}).compose({}, kWidth, kHeight), x, y);
    ASSERT_TRUE(inside.hit);
    ASSERT_TRUE(outside.hit);

    EXPECT_EQ(outside.lensSet, 0u);
    EXPECT_EQ(outside.layer, 0);
    EXPECT_EQ(outside.layerName, "outside");
    EXPECT_EQ(outside.kind, GeometryKind::Triangle);
    EXPECT_EQ(outside.objectName, "outer cube");
    EXPECT_EQ(outside.materialName, "outer cube");

    EXPECT_EQ(inside.lensSet, 1u);
    EXPECT_EQ(inside.layer, 1);
    EXPECT_EQ(inside.layerName, "inner cube");
    EXPECT_EQ(inside.objectName, "inner cube");
    EXPECT_EQ(inside.materialName, "inner cube");
    EXPECT_EQ(scene.meshes[inside.geometry].name, "inner cube");
    EXPECT_TRUE(inside.nodeName.empty()) << "built-in geometry has no glTF node";
    EXPECT_EQ(inside.sourceNode, -1);

    // One ray, two depths: the inner cube lies behind the outer cube's front.
    EXPECT_EQ(inside.ray.direction, outside.ray.direction);
    EXPECT_EQ(inside.samplePosition, glm::vec2(float(x) + 0.5f, float(y) + 0.5f));
    EXPECT_GT(inside.distance, outside.distance);
    for (const PickResult *p : {&inside, &outside}) {
        const glm::vec3 onRay = p->ray.at(p->distance);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(p->scenePosition[c], onRay[c], 1e-4f);
            EXPECT_EQ(p->worldPosition[c], double(p->scenePosition[c])) << "the built-in scene is not re-centred";
        }
        expectUnit(p->shadingNormal);
        expectUnit(p->geometricNormal);
        EXPECT_TRUE(p->frontFacing);
        EXPECT_LT(glm::dot(p->geometricNormal, p->ray.direction), 0.f);
    }
    // On the inner cube's surface: |p − centre| reaches the half size 0.45 on one axis.
    const glm::vec3 q = glm::abs(inside.scenePosition - glm::vec3(0.f, 1.f, 0.f));
    EXPECT_NEAR(std::max({q.x, q.y, q.z}), 0.45f, 1e-4f);
}

TEST(Picking, MissesAndHiddenLayersReportNoHit) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    // Level with the cubes: the upper half of the image looks into the sky.
    const Camera camera = Camera::lookAt({0.f, 1.f, 8.f}, {0.f, 1.f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    const PolicyMap plain(kWidth, kHeight, RayPolicy{});

    const PickResult sky = pick(tracer, camera, plain, kWidth / 2, 0);
    EXPECT_FALSE(sky.hit);
    EXPECT_GT(sky.ray.direction.y, 0.f) << "the ray is set even for a miss";
    EXPECT_FALSE(pick(tracer, camera, plain, -1, 3).hit);
    EXPECT_FALSE(pick(tracer, camera, plain, 3, kHeight).hit);

    // What a lens hides cannot be picked: a layer lens showing no layer leaves nothing to hit.
    ASSERT_TRUE(pick(tracer, camera, plain, kWidth / 2, kHeight / 2).hit);
    const LensStack hideAll = stackOf({pluginLens("layer", LensRegion::ellipse({0.5f, 0.5f}, {0.3f, 0.3f}),
                                                  {{"layers", "none"}})});
    const PickResult hidden = pick(tracer, camera, hideAll.compose({}, kWidth, kHeight), kWidth / 2, kHeight / 2);
    EXPECT_FALSE(hidden.hit);
    EXPECT_EQ(hidden.lensSet, 1u);
}

TEST(Picking, AgreesWithPixelProbeOnEveryPixelOfARealModelUnderALensStack) {
    const Scene scene = loadScene((std::filesystem::path(MVCL_TEST_DATA_DIR) / "models" / "HRA_Kidney_Female_Left" /
                                   "VH_F_Kidney_L.glb")
                                      .string());
    ASSERT_GE(scene.layers.count(), 3);
    const Tracer tracer(scene);
    constexpr int width = 56, height = 48;
    const Camera camera = Camera::framing(scene.bounds(), 40.f, float(width) / float(height));

    // Overlapping layer lenses with feathered edges, and a magnifier (ray shaping) over part of them.
    LensRegion outer = LensRegion::ellipse({0.45f, 0.5f}, {0.55f, 0.65f});
    outer.setFeather(3.f);
    LensRegion deeper = LensRegion::rectangle({0.6f, 0.45f}, {0.3f, 0.35f});
    deeper.setFeather(2.f);
    const LensStack stack = stackOf({pluginLens("layer", outer, {{"layers", "1-"}}),
                                     pluginLens("layer", deeper, {{"layers", "2-"}}),
                                     pluginLens("magnifier", LensRegion::ellipse({0.35f, 0.6f}, {0.25f, 0.25f}),
                                                {{"magnification", "2"}})});
    const PixelProbe probe(stack, width, height);

    int hits = 0, shaped = 0;
    bool seen[3] = {false, false, false};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const PickResult p = probe.pick(tracer, camera, x, y);
            const std::optional<Hit> hit = probe.primaryHit(tracer, camera, x, y);
            const std::optional<int> layer = probe.primaryHitLayer(tracer, camera, x, y);
            ASSERT_EQ(p.hit, layer.has_value()) << x << "," << y;
            if (!p.hit) continue;
            ++hits;
            EXPECT_EQ(p.layer, *layer) << x << "," << y;
            EXPECT_EQ(p.distance, hit->t) << x << "," << y;
            EXPECT_EQ(p.geometry, hit->geometry) << x << "," << y;
            EXPECT_EQ(p.primitive, hit->primitive) << x << "," << y;
            // The pick honours the pixel's composed mask: hidden layers are never picked.
            const PixelPolicy &policy = probe.policy(x, y);
            EXPECT_EQ(p.lensSet, policy.lensSet);
            EXPECT_NE(policy.ray.query(RayType::Primary).layerMask & layerBit(p.layer), 0u) << x << "," << y;
            if (policy.isShaped()) ++shaped;
            if (p.layer < 3) seen[p.layer] = true;
            EXPECT_FALSE(p.objectName.empty());
            EXPECT_EQ(p.objectName, scene.meshes[p.geometry].name);
            EXPECT_EQ(p.nodeName, scene.meshes[p.geometry].nodeName);
            EXPECT_GE(p.sourceNode, 0);
        }
    EXPECT_GT(hits, width * height / 8);
    EXPECT_GT(shaped, 0) << "the magnifier's pixels are part of the comparison";
    EXPECT_TRUE(seen[0] && seen[1] && seen[2]) << "every layer shows somewhere";
}

TEST(Picking, WorldPositionOfAModelFarFromTheOrigin) {
    // A 2 × 2 square in a node translated millions of units away, with named node, mesh and material.
    test::GltfWriter w;
    const int pos = w.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
    const int idx = w.indices16({0, 1, 2, 0, 2, 3});
    w.doc["materials"] = nlohmann::json::array({{{"name", "FarPaint"}}});
    const int mesh = w.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"material", 0}}, "QuadMesh");
    const glm::dvec3 translation(1e7 + 0.25, -3e6 + 0.125, 5e5);
    w.scene({w.node({{"mesh", mesh},
                     {"name", "FarQuad"},
                     {"translation", {translation.x, translation.y, translation.z}}})});
    const Scene scene = w.load();
    ASSERT_NEAR(scene.worldOrigin.x, translation.x, 1e-9);
    const Tracer tracer(scene);
    // An oblique view of the square (scene space).
    const Camera camera = Camera::lookAt({0.5f, 0.3f, 3.f}, {0.2f, -0.1f, 0.f}, {0.f, 1.f, 0.f}, 40.f);
    const PickResult p = pick(tracer, camera, PolicyMap(kWidth, kHeight, RayPolicy{}), kWidth / 2 + 3, kHeight / 2 - 2);
    ASSERT_TRUE(p.hit);
    EXPECT_EQ(p.nodeName, "FarQuad");
    EXPECT_EQ(p.objectName, "FarQuad");
    EXPECT_EQ(p.meshName, "QuadMesh");
    EXPECT_EQ(p.materialName, "FarPaint");
    EXPECT_EQ(p.sourceNode, 0);
    EXPECT_EQ(p.sourceMesh, 0);

    // The same ray in world space, in double, meets the plane z = translation.z.
    const glm::dvec3 eye = glm::dvec3(p.ray.origin) + scene.worldOrigin;
    const glm::dvec3 direction(p.ray.direction);
    const double t = (translation.z - eye.z) / direction.z;
    const glm::dvec3 expected = eye + t * direction;
    EXPECT_NEAR(double(p.distance), t, 1e-5);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.worldPosition[c], expected[c], 1e-5) << "axis " << c;
    EXPECT_GT(std::fabs(p.worldPosition.x - translation.x), 0.01) << "a point off the square's centre";
    EXPECT_LT(std::fabs(p.worldPosition.x - translation.x), 1.0);
}
