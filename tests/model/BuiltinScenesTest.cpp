#include <mvcl/model/BuiltinScenes.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

using namespace mvcl;

TEST(BuiltinScenes, DefaultSceneIsThePapersCubeInCube) {
    const auto names = builtinSceneNames();
    ASSERT_FALSE(names.empty());
    EXPECT_EQ(names.front(), "cube-in-cube");
    const Scene s = makeBuiltinScene("cube-in-cube");
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].layer, 0);
    EXPECT_EQ(s.meshes[1].layer, 1);
    EXPECT_EQ(s.triangleCount(), 24u);
    ASSERT_EQ(s.spheres.size(), 2u);
    ASSERT_EQ(s.planes.size(), 1u);
    ASSERT_EQ(s.lights.size(), 1u);
    // One sphere reflects, one refracts.
    EXPECT_GT(s.materials[s.spheres[0].material].reflectivity, 0.5f);
    EXPECT_GT(s.materials[s.spheres[1].material].transparency, 0.5f);
    EXPECT_GT(s.materials[s.spheres[1].material].ior, 1.f);
    // The inner cube lies strictly inside the outer one.
    Bounds3f outer, inner;
    for (const auto &p : s.meshes[0].positions) outer.expand(p);
    for (const auto &p : s.meshes[1].positions) inner.expand(p);
    EXPECT_TRUE(outer.contains(inner.min) && outer.contains(inner.max));
    EXPECT_EQ(s.layers.count(), 2);
}

TEST(BuiltinScenes, OnionHasFourNestedLayers) {
    const Scene s = makeBuiltinScene("onion");
    ASSERT_EQ(s.spheres.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(s.spheres[i].layer, i);
        if (i > 0) {
            EXPECT_LT(s.spheres[i].radius, s.spheres[i - 1].radius);
        }
    }
    EXPECT_EQ(s.layers.count(), 4);
}

TEST(BuiltinScenes, UnknownNameIsAnErrorListingTheKnownOnes) {
    try {
        makeBuiltinScene("teapot");
        FAIL() << "no exception";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("cube-in-cube"), std::string::npos);
    }
}

TEST(LayerTable, EnsureKeepsLayersSortedAndRejectsOutOfRange) {
    LayerTable t;
    t.ensure(3).name = "deep";
    t.ensure(0);
    t.ensure(3);
    ASSERT_EQ(t.count(), 2);
    EXPECT_EQ(t.layers()[0].id, 0);
    EXPECT_EQ(t.find(3)->name, "deep");
    EXPECT_EQ(t.find(2), nullptr);
    EXPECT_THROW(t.ensure(32), Error);
    EXPECT_THROW(t.ensure(-1), Error);
    EXPECT_EQ(layersFrom(1), 0xfffffffeu);
    EXPECT_EQ(layersFrom(0), kAllLayers);
    EXPECT_EQ(layersFrom(32), 0u);
}
