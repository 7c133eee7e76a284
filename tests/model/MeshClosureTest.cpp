// recordMeshClosure: which meshes bound a solid, the property clip caps rely on.

#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/MeshClosure.h>
#include <mvcl/model/Scene.h>

#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <utility>

namespace mvcl {
namespace {

using test::splitFaceBox;

MeshClosure closureOf(std::vector<TriangleMesh> meshes) {
    Scene scene;
    scene.meshes = std::move(meshes);
    recordMeshClosure(scene);
    return scene.meshes.front().closure;
}

TEST(MeshClosure, ABoxWithVerticesSplitAtItsSeamsIsClosedOutward) {
    EXPECT_EQ(closureOf({splitFaceBox({0, 0, 0}, {1, 2, 3})}), MeshClosure::Outward);
}

TEST(MeshClosure, ReversedWindingIsClosedInward) {
    TriangleMesh box = splitFaceBox({0, 0, 0}, {1, 1, 1});
    for (glm::uvec3 &tri : box.indices) std::swap(tri.y, tri.z);
    EXPECT_EQ(closureOf({box}), MeshClosure::Inward);
}

TEST(MeshClosure, AMissingTriangleOpensTheMesh) {
    TriangleMesh box = splitFaceBox({0, 0, 0}, {1, 1, 1});
    box.indices.pop_back();
    EXPECT_EQ(closureOf({box}), MeshClosure::Open);
}

TEST(MeshClosure, OneFlippedTriangleOpensTheMesh) {
    // Its edges are then used twice in one direction.
    TriangleMesh box = splitFaceBox({0, 0, 0}, {1, 1, 1});
    std::swap(box.indices[3].y, box.indices[3].z);
    EXPECT_EQ(closureOf({box}), MeshClosure::Open);
}

TEST(MeshClosure, AnEdgeSharedByFourTrianglesIsNotClosed) {
    // Two boxes touching along one edge share it four times: not a manifold solid.
    TriangleMesh pair = splitFaceBox({0, 0, 0}, {1, 1, 1});
    const TriangleMesh other = splitFaceBox({1, 1, 0}, {2, 2, 1});
    const uint32_t base = uint32_t(pair.positions.size());
    pair.positions.insert(pair.positions.end(), other.positions.begin(), other.positions.end());
    for (const glm::uvec3 &tri : other.indices) pair.indices.push_back(tri + base);
    EXPECT_EQ(closureOf({pair}), MeshClosure::Open);
}

TEST(MeshClosure, DegenerateTrianglesAreIgnored) {
    TriangleMesh box = splitFaceBox({0, 0, 0}, {1, 1, 1});
    box.indices.push_back({0, 0, 1}); // two corners the same: no area
    EXPECT_EQ(closureOf({box}), MeshClosure::Outward);
}

TEST(MeshClosure, AFlatDoubleSidedSheetIsNotASolid) {
    // Both windings of one quad: every edge is used once each way, but nothing is enclosed.
    TriangleMesh sheet;
    sheet.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    sheet.indices = {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 3, 2}};
    EXPECT_EQ(closureOf({sheet}), MeshClosure::Open);
}

TEST(MeshClosure, MeshesOfOneGltfNodeAreJudgedTogether) {
    // A box whose faces use two materials becomes two meshes of the same node: each is open on
    // its own, together they bound the solid.
    TriangleMesh box = splitFaceBox({0, 0, 0}, {1, 1, 1});
    TriangleMesh top = box, rest = box;
    top.indices.assign(box.indices.begin(), box.indices.begin() + 2);
    rest.indices.assign(box.indices.begin() + 2, box.indices.end());
    top.sourceNode = rest.sourceNode = 3;
    top.sourceMesh = rest.sourceMesh = 1;
    Scene scene;
    scene.meshes = {top, rest};
    recordMeshClosure(scene);
    EXPECT_EQ(scene.meshes[0].closure, MeshClosure::Outward);
    EXPECT_EQ(scene.meshes[1].closure, MeshClosure::Outward);
    // The same pieces from different nodes are two open meshes.
    scene.meshes[1].sourceNode = 4;
    recordMeshClosure(scene);
    EXPECT_EQ(scene.meshes[0].closure, MeshClosure::Open);
    EXPECT_EQ(scene.meshes[1].closure, MeshClosure::Open);
}

TEST(MeshClosure, TheBuiltinCubesAreClosed) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    ASSERT_EQ(scene.meshes.size(), 2u);
    for (const TriangleMesh &mesh : scene.meshes) EXPECT_EQ(mesh.closure, MeshClosure::Outward) << mesh.name;
}

TEST(MeshClosure, TheGltfLoaderRecordsIt) {
    const std::filesystem::path models = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";
    EXPECT_EQ(loadGltf(models / "Box" / "Box.glb").meshes.front().closure, MeshClosure::Outward);
    // The avocado's surface is not watertight: some edges are not used once each way.
    EXPECT_EQ(loadGltf(models / "Avocado" / "Avocado.glb").meshes.front().closure, MeshClosure::Open);
    const Scene body = loadGltf(models / "HRA_Female_Body" / "HRA_Female_Body.glb");
    for (const TriangleMesh &mesh : body.meshes)
        if (mesh.name == "VH_F_skin" || mesh.name == "VH_F_sacrum") {
            EXPECT_EQ(mesh.closure, MeshClosure::Outward) << mesh.name;
        }
}

} // namespace
} // namespace mvcl
