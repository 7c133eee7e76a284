// Memory ceilings for OBJ, STL and PLY: a file whose geometry would not fit the budget is refused
// with the estimate, before its geometry is read. Binary STL and PLY headers are believed from
// the file's first bytes (the tests claim 20 million triangles and 50 million faces in sparse
// files, which cost no disk and, unread, no memory); OBJ and ASCII STL are counted.

#include <mvcl/model/MeshFileLoader.h>

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>

#include <mvcl/testing/ErrorOf.h>

#include "ProcessMemory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace mvcl {
namespace {

using test::errorOf;
using test::peakResidentMiB;

fs::path scratch(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-mesh-budget-test";
    fs::create_directories(dir);
    return dir / name;
}

/// `header`, then zeros up to `size` bytes without writing them (a sparse file).
void writeSparse(const fs::path &file, const std::string &header, std::uint64_t size) {
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(header.data(), std::streamsize(header.size()));
    fs::resize_file(file, size);
}

SceneLoadOptions budgetMiB(std::uint64_t mebibytes) {
    SceneLoadOptions options;
    options.memoryBudgetBytes = mebibytes << 20;
    return options;
}

MeshFileOptions budget(std::uint64_t bytes) {
    MeshFileOptions options;
    options.maxGeometryBytes = bytes;
    return options;
}

/// An OBJ grid of n × n quads: (n+1)² vertices, 2n² triangles.
std::string objGrid(int n) {
    std::ostringstream obj;
    obj << "o grid\n";
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) obj << "v " << x << " " << y << " 0\n";
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const int a = y * (n + 1) + x + 1;
            obj << "f " << a << " " << a + 1 << " " << a + n + 2 << " " << a + n + 1 << "\n";
        }
    return obj.str();
}

TEST(MeshFileMemoryBudget, ABinaryStlClaimingTwentyMillionTrianglesIsRefusedFromItsHeader) {
    const std::uint32_t triangles = 20'000'000;
    std::string header(80, ' ');
    header.append(reinterpret_cast<const char *>(&triangles), 4);
    const fs::path file = scratch("claims.stl");
    writeSparse(file, header, 84 + std::uint64_t(triangles) * 50); // exactly what the count needs: a valid size
    const long before = peakResidentMiB();
    const std::string error = errorOf([&] { loadScene(file.string(), budgetMiB(1024)); });
    EXPECT_EQ(error.rfind(file.string() + ": its geometry would need about ", 0), 0u) << error;
    // 20 000 000 × 168 + 10 000 000 × 104 bytes and the file's 1 000 000 084 = 5150 MiB.
    EXPECT_NE(error.find("about 5150 MiB (20000000 triangles, 10000000 vertices"), std::string::npos) << error;
    EXPECT_NE(error.find("more than the memory budget of 1024 MiB; refused before loading it"), std::string::npos) << error;
    EXPECT_LT(peakResidentMiB() - before, 100) << "the 1 GB file was read after all";
    fs::remove(file);
}

TEST(MeshFileMemoryBudget, APlyClaimingFiftyMillionFacesIsRefusedFromItsHeader) {
    const std::string header = "ply\nformat binary_little_endian 1.0\ncomment sparse\nelement vertex 25000000\n"
                               "property float x\nproperty float y\nproperty float z\nelement face 50000000\n"
                               "property list uchar int vertex_indices\nend_header\n";
    const fs::path file = scratch("claims.ply");
    // What the counts need at least: 12 bytes a vertex, 13 a triangle.
    writeSparse(file, header, header.size() + 25'000'000ull * 12 + 50'000'000ull * 13);
    const long before = peakResidentMiB();
    const std::string error = errorOf([&] { loadScene(file.string(), budgetMiB(2048)); });
    EXPECT_EQ(error.rfind(file.string() + ": its geometry would need about ", 0), 0u) << error;
    EXPECT_NE(error.find("(50000000 triangles, 25000000 vertices"), std::string::npos) << error;
    EXPECT_NE(error.find("more than the memory budget of 2048 MiB"), std::string::npos) << error;
    EXPECT_LT(peakResidentMiB() - before, 100) << "the 950 MB file was read after all";
    fs::remove(file);

    // The same header on a file that cannot hold it: the budget speaks first, nothing is allocated.
    const std::string ascii = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 50000000\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string small = errorOf([&] {
        loadMeshFileFromMemory({reinterpret_cast<const std::uint8_t *>(ascii.data()), ascii.size()}, "small.ply",
                               MeshFormat::Ply, budget(64ull << 20));
    });
    EXPECT_NE(small.find("small.ply: its geometry would need about"), std::string::npos) << small;
    EXPECT_NE(small.find("(50000000 triangles, 3 vertices"), std::string::npos) << small;
}

TEST(MeshFileMemoryBudget, AnObjIsCountedAndRefusedOnlyWhenItsGeometryDoesNotFit) {
    const fs::path file = scratch("grid.obj");
    std::ofstream(file) << objGrid(100); // 10 201 vertices, 20 000 triangles
    const std::string error = errorOf([&] { loadScene(file.string(), budgetMiB(1)); });
    EXPECT_NE(error.find(file.string() + ": its geometry would need about"), std::string::npos) << error;
    EXPECT_NE(error.find("(20000 triangles, 10201 vertices"), std::string::npos) << error << "\n(the pre-count is exact)";
    const Scene scene = loadScene(file.string(), budgetMiB(64));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].indices.size(), 20000u);
}

TEST(MeshFileMemoryBudget, AnAsciiStlIsCounted) {
    std::ostringstream stl;
    stl << "solid strip\n";
    for (int i = 0; i < 3000; ++i)
        stl << "facet normal 0 0 1\nouter loop\nvertex " << i << " 0 0\nvertex " << i + 1 << " 0 0\nvertex " << i
            << " 1 0\nendloop\nendfacet\n";
    stl << "endsolid strip\n";
    const std::string text = stl.str();
    const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t *>(text.data()), text.size());
    const std::string error = errorOf([&] {
        loadMeshFileFromMemory(bytes, "strip.stl", MeshFormat::Stl, budget(100'000));
    });
    EXPECT_NE(error.find("strip.stl: its geometry would need about"), std::string::npos) << error;
    EXPECT_NE(error.find("(3000 triangles, 1500 vertices"), std::string::npos) << error;
    EXPECT_NO_THROW(loadMeshFileFromMemory(bytes, "strip.stl", MeshFormat::Stl, budget(64ull << 20)));
}

} // namespace
} // namespace mvcl
