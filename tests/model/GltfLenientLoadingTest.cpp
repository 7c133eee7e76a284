// Files the glTF-Validator accepts load; files whose only errors are in parts mvcl does not render
// load their geometry with a warning naming the part; unsupported required extensions are named
// even where tinygltf fails first; error messages never carry raw bytes of the file.

#include "GltfTestWriter.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/GltfLoader.h>

#include <gtest/gtest.h>

#include <algorithm>

using namespace mvcl;
using namespace mvcl::test;

namespace {

bool hasWarningWith(const Scene &s, const std::string &text) {
    return std::any_of(s.report.warnings.begin(), s.report.warnings.end(),
                       [&](const std::string &w) { return w.find(text) != std::string::npos; });
}

std::string errorOf(const std::string &text) {
    try {
        loadGltfFromMemory(asBytes(text), "file.gltf", std::filesystem::temp_directory_path());
    } catch (const Error &e) {
        return e.what();
    }
    return "(loaded)";
}

Scene load(const std::string &text) {
    return loadGltfFromMemory(asBytes(text), "file.gltf", std::filesystem::temp_directory_path());
}

} // namespace

TEST(GltfLenientLoading, UnusedBufferWithoutUriInAGltfLoadsWithAWarning) {
    GltfWriter w = triangleFile();
    nlohmann::json doc = nlohmann::json::parse(w.text());
    doc["buffers"].push_back({{"byteLength", 16}});
    const Scene s = load(doc.dump());
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_TRUE(hasWarningWith(s, "buffer 1 has no uri and nothing reads it; ignored"));
}

TEST(GltfLenientLoading, ReadBufferWithoutUriInAGltfIsNamedCorrectly) {
    GltfWriter w = triangleFile();
    nlohmann::json doc = nlohmann::json::parse(w.text());
    doc["buffers"][0].erase("uri");
    const std::string e = errorOf(doc.dump());
    EXPECT_NE(e.find("buffer 0 has no uri, but bufferViews read it"), std::string::npos) << e;
    EXPECT_EQ(e.find("absolute path"), std::string::npos) << e;
}

TEST(GltfLenientLoading, MinVersionAboveAVersionOf2Point0IsReadAs2Point0) {
    GltfWriter w = triangleFile();
    w.doc["asset"]["minVersion"] = "2.1";
    const Scene s = w.load();
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_TRUE(hasWarningWith(s, "asset.minVersion '2.1' is above asset.version 2.0"));
    // A file that really needs 2.1 is still refused.
    w.doc["asset"]["version"] = "2.1";
    EXPECT_NE(errorOf(w.text()).find("asset.minVersion '2.1' is newer"), std::string::npos);
}

TEST(GltfLenientLoading, PercentEncodedDataUriBuffersLoad) {
    GltfWriter w = triangleFile();
    nlohmann::json doc = nlohmann::json::parse(w.text());
    std::string encoded;
    static const char *kHex = "0123456789ABCDEF";
    for (std::uint8_t b : w.bin) {
        encoded += '%';
        encoded += kHex[b >> 4];
        encoded += kHex[b & 15];
    }
    doc["buffers"][0]["uri"] = "data:application/octet-stream," + encoded;
    const Scene s = load(doc.dump());
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_TRUE(hasWarningWith(s, "buffer 0: data URI re-encoded as base64"));
    // Another media type with base64 data.
    doc["buffers"][0]["uri"] = "data:application/x-binary;base64," + base64(w.bin);
    EXPECT_EQ(load(doc.dump()).triangleCount(), 1u);
}

TEST(GltfLenientLoading, DracoIsNamedEvenWhereTinygltfWouldFailFirst) {
    GltfWriter w = triangleFile();
    w.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    w.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    // Draco files have accessors without a bufferView index that tinygltf would trip over.
    w.doc["accessors"][0]["bufferView"] = 7;
    const std::string e = errorOf(w.text());
    EXPECT_NE(e.find("requires extension KHR_draco_mesh_compression"), std::string::npos) << e;
}

TEST(GltfLenientLoading, ABrokenCameraDoesNotThrowAwayTheModel) {
    GltfWriter w = triangleFile();
    w.doc["cameras"] = {{{"type", "perspective"}, {"perspective", "not an object"}}};
    w.doc["nodes"][0]["camera"] = 0;
    const Scene s = w.load();
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_TRUE(s.cameras.empty());
    EXPECT_TRUE(hasWarningWith(s, "loaded without its cameras")) << s.report.warnings.front();
}

TEST(GltfLenientLoading, BrokenAnimationsAndSkinsAreDropped) {
    GltfWriter w = triangleFile();
    // An animation sampler without its required input: tinygltf refuses the whole file.
    w.doc["animations"] = {{{"channels", nlohmann::json::array()}, {"samplers", {{{"output", 0}}}}}};
    const Scene s = w.load();
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_TRUE(hasWarningWith(s, "loaded without its animations"));
}

TEST(GltfLenientLoading, BrokenMaterialsFallBackToTheDefault) {
    GltfWriter w = triangleFile();
    w.doc["materials"] = {{{"emissiveFactor", {1.0}}}}; // tinygltf refuses a length of 1
    w.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const Scene s = w.load();
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_TRUE(hasWarningWith(s, "loaded without its materials"));
    EXPECT_TRUE(hasWarningWith(s, "emissiveFactor")); // tinygltf's reason is quoted
}

TEST(GltfLenientLoading, BrokenGeometryIsStillRefusedWithTinygltfsFirstMessage) {
    GltfWriter w = triangleFile();
    w.doc["accessors"][0]["count"] = "three";
    const std::string e = errorOf(w.text());
    EXPECT_NE(e.find("not a valid glTF file"), std::string::npos) << e;
}

TEST(GltfLenientLoading, IndexOutOfRangeIsAnError) {
    GltfWriter w;
    const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int idx = w.indices16({0, 1, 3});
    const int m = w.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
    w.scene({w.node({{"mesh", m}})});
    EXPECT_NE(errorOf(w.text()).find("index 2 is 3, but the primitive has only 3 vertices"), std::string::npos);
    // An attribute or indices accessor index past the accessors is an error, not 0 triangles.
    w.doc["meshes"][0]["primitives"][0]["indices"] = 9;
    EXPECT_NE(errorOf(w.text()), "(loaded)");
}

TEST(GltfLenientLoading, MessagesNeverCarryRawBytes) {
    GltfWriter w = triangleFile();
    nlohmann::json doc = nlohmann::json::parse(w.text());
    doc["buffers"][0]["uri"] = std::string("bad\x80\x01name\xff.bin", 13);
    const std::string text = doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::ignore);
    const std::string e = errorOf(std::string("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":36,\"uri\":\"bad\x80\x01name\xff.bin\"}]}"));
    for (unsigned char c : e) EXPECT_TRUE(c >= 0x20 && c < 0x80) << e;
    (void)text;
}
