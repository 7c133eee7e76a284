// Memory ceilings: a model whose geometry (meshes, one copy per instance, and the BVH) would need
// more than the budget is refused before its geometry is read, with the estimate in the error;
// the estimate counts what the loader would build.

#include <mvcl/model/GltfLoader.h>

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>

#include <mvcl/testing/ErrorOf.h>

#include "ProcessMemory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <regex>
#include <string>

namespace mvcl {
namespace {

const std::filesystem::path kModels = std::filesystem::path(MVCL_TEST_DATA_DIR) / "models";

using test::errorOf;
using test::peakResidentMiB;

TEST(GltfMemoryBudget, ATwentyMillionTriangleFileIsRefusedWithItsEstimateWithoutReadingIt) {
    // 60 million positions that claim 20 million triangles: an accessor without a bufferView
    // reads as zeros, so the file is a few hundred bytes, and only reading it would cost 720 MB.
    const std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"componentType": 5126, "count": 60000000, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}]})";
    GltfLoadOptions options;
    options.maxGeometryBytes = 1ull << 30;
    const long before = peakResidentMiB();
    const std::string error = errorOf([&] {
        loadGltfFromMemory({reinterpret_cast<const std::uint8_t *>(json.data()), json.size()}, "claims.gltf", ".", options);
    });
    EXPECT_EQ(error.rfind("claims.gltf: ", 0), 0u) << error;
    // 20 000 000 × 156 + 60 000 000 × 56 bytes = 6 180 MiB.
    EXPECT_NE(error.find("about 6180 MiB (20000000 triangles, 60000000 vertices"), std::string::npos) << error;
    EXPECT_NE(error.find("more than the memory budget of 1024 MiB"), std::string::npos) << error;
    EXPECT_LT(peakResidentMiB() - before, 100) << "the refused geometry was read after all";
}

TEST(GltfMemoryBudget, TheEstimateCountsEveryInstancesTriangles) {
    // 2CylinderEngine instances its meshes: the estimate must count each copy, as the loader does.
    const std::filesystem::path engine = kModels / "2CylinderEngine" / "2CylinderEngine.glb";
    const Scene loaded = loadGltf(engine);
    // The file's triangles: those loaded and the degenerate ones the loader drops.
    const double triangles = double(loaded.triangleCount() + loaded.report.degenerateTrianglesDropped);
    GltfLoadOptions tight;
    tight.maxGeometryBytes = 1ull << 20;
    const std::string error = errorOf([&] { loadGltf(engine, tight); });
    std::smatch match;
    ASSERT_TRUE(std::regex_search(error, match, std::regex("about [0-9]+ MiB \\(([0-9]+) triangles"))) << error;
    EXPECT_EQ(std::stod(match[1]), triangles) << error;

    GltfLoadOptions roomy;
    roomy.maxGeometryBytes = 1ull << 30;
    EXPECT_EQ(loadGltf(engine, roomy).meshes.size(), loaded.meshes.size());
}

TEST(GltfMemoryBudget, TheSceneLoaderAppliesTheBudgetAndDefaultsToHalfThePhysicalMemory) {
    SceneLoadOptions options;
    options.memoryBudgetBytes = 1ull << 20;
    const std::string engine = (kModels / "2CylinderEngine" / "2CylinderEngine.glb").string();
    const std::string error = errorOf([&] { loadScene(engine, options); });
    EXPECT_NE(error.find("more than the memory budget of 1 MiB"), std::string::npos) << error;
    EXPECT_GT(defaultMemoryBudgetBytes(), 64ull << 20);
    EXPECT_NO_THROW(loadScene(engine)); // the default budget
}

} // namespace
} // namespace mvcl
