/// Catalogue D (cases 30–36 of docs/robustness.md): hostile glTF files, generated here, each
/// written into a folder of its own and loaded through loadGltf(path) exactly like a user's file.
/// Every file must end in a clean mvcl::Error that names the file and the problem, or in a scene
/// (with a warning where the file is suspicious); never in a crash, a hang or a read outside the
/// folder. scripts/ci-sanitizers.sh runs these under ASan/UBSan, and tests/fuzz seeds from them.

#include "GltfTestWriter.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/GltfLoader.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

using namespace mvcl;
using namespace mvcl::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using Bytes = std::vector<std::uint8_t>;

enum class Expect { Reject, Load, LoadWithWarning };

struct HostileFile {
    std::string name;  ///< test name and file stem
    int catalogueCase; ///< 30–36
    Expect expect;
    /// Must appear in the error message (Reject) or in one of the warnings (LoadWithWarning).
    std::string fragment;
    /// Writes companion files into the folder if needed and returns the file's bytes.
    std::function<Bytes(const fs::path &folder)> make;
    std::function<void(const Scene &)> checkScene = {};
    std::string extension = ".gltf";
};

void PrintTo(const HostileFile &f, std::ostream *os) { *os << f.name; }

Bytes bytesOf(const std::string &text) { return Bytes(text.begin(), text.end()); }

/// Replaces the first occurrence; for spellings nlohmann::json cannot write (1e309, bad URIs).
std::string replaceOnce(std::string text, const std::string &from, const std::string &to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

void writeFile(const fs::path &path, const Bytes &bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char *>(bytes.data()), std::streamsize(bytes.size()));
}

/// A .gltf made by `edit` applied to the one-triangle file.
HostileFile triangleCase(std::string name, int catalogueCase, Expect expect, std::string fragment,
                         std::function<void(GltfWriter &)> edit) {
    return {std::move(name), catalogueCase, expect, std::move(fragment), [edit](const fs::path &) {
                GltfWriter w = triangleFile();
                edit(w);
                return bytesOf(w.text());
            }};
}

/// The triangle with its buffer in an external file whose `uri` is `uri` (companions: none).
HostileFile uriCase(std::string name, std::string uri, std::string fragment) {
    return {std::move(name), 36, Expect::Reject, std::move(fragment),
            [uri](const fs::path &) { return bytesOf(triangleFile().text(uri)); }};
}

/// Indices `idx` (component type 5121/5123/5125) over the triangle's three vertices.
HostileFile indexCase(std::string name, Expect expect, std::string fragment, int componentType,
                      std::vector<std::uint32_t> idx) {
    return {std::move(name), 31, expect, std::move(fragment), [componentType, idx](const fs::path &) {
                GltfWriter w;
                const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
                int acc = 0;
                if (componentType == 5121) acc = w.indices8(std::vector<std::uint8_t>(idx.begin(), idx.end()));
                else if (componentType == 5123) acc = w.indices16(std::vector<std::uint16_t>(idx.begin(), idx.end()));
                else acc = w.indices32(idx);
                w.scene({w.node({{"mesh", w.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", acc}}, "M")}})});
                return bytesOf(w.text());
            }};
}

/// The triangle's POSITION made sparse: base positions `base` (or no bufferView when empty),
/// replaced at `targets` (component type `indexType`) by `values`; `edit` may break it further.
HostileFile sparseCase(std::string name, Expect expect, std::string fragment, std::vector<float> base,
                       int indexType, std::vector<std::uint32_t> targets, std::vector<float> values,
                       std::function<void(json &sparse)> edit = {}, std::function<void(const Scene &)> check = {}) {
    HostileFile f{std::move(name), 32, expect, std::move(fragment),
                  [=](const fs::path &) {
                      GltfWriter w;
                      const int baseView = base.empty() ? -1 : w.view(base);
                      int indexView = 0;
                      if (indexType == 5121)
                          indexView = w.view(std::vector<std::uint8_t>(targets.begin(), targets.end()));
                      else if (indexType == 5123)
                          indexView = w.view(std::vector<std::uint16_t>(targets.begin(), targets.end()));
                      else
                          indexView = w.view(targets);
                      const int valueView = w.view(values);
                      const int acc = w.accessor(baseView, 5126, 3, "VEC3");
                      json sparse = {{"count", targets.size()},
                                     {"indices", {{"bufferView", indexView}, {"componentType", indexType}}},
                                     {"values", {{"bufferView", valueView}}}};
                      if (edit) edit(sparse);
                      w.doc["accessors"][acc]["sparse"] = sparse;
                      w.scene({w.node({{"mesh", w.mesh({{"attributes", {{"POSITION", acc}}}})}})});
                      return bytesOf(w.text());
                  }};
    f.checkScene = std::move(check);
    return f;
}

glm::dvec3 worldPosition(const Scene &s, std::size_t vertex) {
    return glm::dvec3(s.meshes.at(0).positions.at(vertex)) + s.worldOrigin;
}

/// The loaded triangle must be exactly (0,0,0), (1,0,0), (0,1,0).
void expectUnitTriangle(const Scene &s) {
    ASSERT_EQ(s.triangleCount(), 1u);
    EXPECT_EQ(worldPosition(s, 0), glm::dvec3(0, 0, 0));
    EXPECT_EQ(worldPosition(s, 1), glm::dvec3(1, 0, 0));
    EXPECT_EQ(worldPosition(s, 2), glm::dvec3(0, 1, 0));
}

/// A GLB of the triangle with `edit` applied to its bytes.
HostileFile glbCase(std::string name, Expect expect, std::string fragment, std::function<void(Bytes &)> edit) {
    HostileFile f{std::move(name), 36, expect, std::move(fragment), [edit](const fs::path &) {
                      Bytes glb = triangleFile().glb();
                      edit(glb);
                      return glb;
                  }};
    f.extension = ".glb";
    return f;
}

void put32(Bytes &b, std::size_t at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) b.at(at + std::size_t(k)) = std::uint8_t(v >> (8 * k));
}
std::uint32_t get32(const Bytes &b, std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= std::uint32_t(b.at(at + std::size_t(k))) << (8 * k);
    return v;
}

constexpr std::uint64_t k2To64Minus8 = std::numeric_limits<std::uint64_t>::max() - 7;

std::vector<HostileFile> hostileFiles() {
    std::vector<HostileFile> files;
    const auto add = [&](HostileFile f) { files.push_back(std::move(f)); };

    // ---- 30. Range arithmetic: every bound checked in overflow-checked uint64.
    add(triangleCase("bufferView_overrun_by_1_byte", 30, Expect::Reject, "1 bytes past the end of buffer 0",
                     [](GltfWriter &w) { w.doc["bufferViews"][0]["byteLength"] = 37; }));
    add(triangleCase("accessor_overrun_by_1_byte", 30, Expect::Reject,
                     "accessor 0 (POSITION of mesh 0 'Tri') reads 1 bytes past the end of bufferView 0",
                     [](GltfWriter &w) { w.doc["accessors"][0]["byteOffset"] = 1; }));
    add(triangleCase("accessor_count_0", 30, Expect::Reject, "count 0",
                     [](GltfWriter &w) { w.doc["accessors"][0]["count"] = 0; }));
    add(triangleCase("accessor_count_2pow31_minus_1", 30, Expect::Reject, "past the end of bufferView 0",
                     [](GltfWriter &w) { w.doc["accessors"][0]["count"] = 2147483647; }));
    add(triangleCase("accessor_count_2pow31_minus_1_without_bufferView", 30, Expect::Reject,
                     "no bufferView and 2147483647 elements", [](GltfWriter &w) {
                         w.doc["accessors"][0].erase("bufferView");
                         w.doc["accessors"][0]["count"] = 2147483647;
                     }));
    add(triangleCase("accessor_byteOffset_2pow64_minus_8", 30, Expect::Reject, "overflows 64 bits",
                     [](GltfWriter &w) { w.doc["accessors"][0]["byteOffset"] = k2To64Minus8; }));
    add(triangleCase("bufferView_byteOffset_2pow64_minus_8", 30, Expect::Reject,
                     "bufferView 0: byteOffset + byteLength overflows 64 bits",
                     [](GltfWriter &w) { w.doc["bufferViews"][0]["byteOffset"] = k2To64Minus8; }));
    add(triangleCase("byteStride_smaller_than_element", 30, Expect::Reject, "smaller than the element size 12",
                     [](GltfWriter &w) { w.doc["bufferViews"][0]["byteStride"] = 8; }));
    add(triangleCase("byteStride_not_multiple_of_4", 30, Expect::Reject, "byteStride",
                     [](GltfWriter &w) { w.doc["bufferViews"][0]["byteStride"] = 14; }));
    add(triangleCase("byteStride_above_252", 30, Expect::Reject, "byteStride",
                     [](GltfWriter &w) { w.doc["bufferViews"][0]["byteStride"] = 256; }));
    add(triangleCase("byteStride_runs_past_bufferView", 30, Expect::Reject, "past the end of bufferView 0",
                     [](GltfWriter &w) { w.doc["bufferViews"][0]["byteStride"] = 16; }));
    add(triangleCase("componentType_INT_not_in_glTF2", 30, Expect::Reject, "componentType 5124",
                     [](GltfWriter &w) { w.doc["accessors"][0]["componentType"] = 5124; }));
    add(triangleCase("position_accessor_VEC2", 30, Expect::Reject, "must be VEC3",
                     [](GltfWriter &w) { w.doc["accessors"][0]["type"] = "VEC2"; }));
    add(triangleCase("attribute_counts_differ", 30, Expect::Reject, "elements, other attributes have",
                     [](GltfWriter &w) {
                         const int normals = w.accessor(w.view(std::vector<float>{0, 0, 1, 0, 0, 1}), 5126, 2, "VEC3");
                         w.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = normals;
                     }));

    // ---- 31. Indices.
    add(indexCase("index_equals_vertex_count_u16", Expect::Reject, "index 2 is 3, but the primitive has only 3 vertices",
                  5123, {0, 1, 3}));
    add(indexCase("index_huge_u32", Expect::Reject, "index 1 is 4000000000", 5125, {0, 4000000000u, 2}));
    add(indexCase("primitive_restart_u8", Expect::Reject, "primitive-restart value 255", 5121, {0, 1, 255}));
    add(indexCase("primitive_restart_u16", Expect::Reject, "primitive-restart value 65535", 5123, {0, 1, 65535}));
    add(indexCase("primitive_restart_u32", Expect::Reject, "primitive-restart value 4294967295", 5125,
                  {0, 1, 0xffffffffu}));
    add(indexCase("triangle_count_not_multiple_of_3", Expect::LoadWithWarning, "5 indices is not a multiple of 3",
                  5123, {0, 1, 2, 0, 1}));
    add({"float_index_accessor", 31, Expect::Reject, "is used as indices but is not an unsigned integer SCALAR",
         [](const fs::path &) {
             GltfWriter w;
             const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
             const int idx = w.accessor(w.view(std::vector<float>{0, 1, 2}), 5126, 3, "SCALAR");
             w.scene({w.node({{"mesh", w.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
             return bytesOf(w.text());
         }});
    add({"signed_short_index_accessor", 31, Expect::Reject, "is not an unsigned integer SCALAR",
         [](const fs::path &) {
             GltfWriter w;
             const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
             const int idx = w.accessor(w.view(std::vector<std::int16_t>{0, 1, 2}), 5122, 3, "SCALAR");
             w.scene({w.node({{"mesh", w.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
             return bytesOf(w.text());
         }});

    // ---- 32. Sparse accessors.
    const std::vector<float> base = {0, 0, 0, 9, 9, 9, 0, 1, 0};
    const auto movedVertex1 = [](const Scene &s) { expectUnitTriangle(s); };
    add(sparseCase("sparse_valid_u8_indices", Expect::Load, "", base, 5121, {1}, {1, 0, 0}, {}, movedVertex1));
    add(sparseCase("sparse_valid_u16_indices", Expect::Load, "", base, 5123, {1}, {1, 0, 0}, {}, movedVertex1));
    add(sparseCase("sparse_valid_u32_indices", Expect::Load, "", base, 5125, {1}, {1, 0, 0}, {}, movedVertex1));
    add(sparseCase("sparse_without_base_bufferView", Expect::Load, "", {}, 5123, {1, 2}, {1, 0, 0, 0, 1, 0}, {},
                   movedVertex1)); // zeros, then two vertices replaced
    add(sparseCase("sparse_indices_decreasing", Expect::Reject, "sparse indices are not strictly increasing", base,
                   5123, {2, 1}, {0, 1, 0, 1, 0, 0}));
    add(sparseCase("sparse_indices_repeated", Expect::Reject, "sparse indices are not strictly increasing", base, 5123,
                   {1, 1}, {1, 0, 0, 1, 0, 0}));
    add(sparseCase("sparse_index_out_of_range", Expect::Reject, "sparse index 3 is not below count 3", base, 5125,
                   {3}, {1, 0, 0}));
    add(sparseCase("sparse_count_above_accessor_count", Expect::Reject, "sparse count 4 is not in [1, 3]", base, 5123,
                   {1}, {1, 0, 0}, [](json &s) { s["count"] = 4; }));
    add(sparseCase("sparse_count_2pow31_minus_1", Expect::Reject, "sparse count 2147483647", base, 5123, {1},
                   {1, 0, 0}, [](json &s) { s["count"] = 2147483647; }));
    add(sparseCase("sparse_values_past_bufferView", Expect::Reject, "sparse values read past the end of bufferView",
                   base, 5123, {1}, {1, 0, 0}, [](json &s) { s["values"]["byteOffset"] = 4; }));
    add(sparseCase("sparse_index_float_type", Expect::Reject, "is not an unsigned integer type", base, 5123, {1},
                   {1, 0, 0}, [](json &s) { s["indices"]["componentType"] = 5126; }));

    // ---- 34. Non-finite and extreme transforms.
    add({"position_NaN", 34, Expect::Reject, "position 1 is (1.000000, nan, 0.000000), not finite",
         [](const fs::path &) {
             GltfWriter w;
             w.scene({w.node({{"mesh", w.mesh({{"attributes",
                                                {{"POSITION", w.positions({0, 0, 0, 1, std::nanf(""), 0, 0, 1, 0})}}}})}})});
             return bytesOf(w.text());
         }});
    add({"position_Inf", 34, Expect::Reject, "not finite", [](const fs::path &) {
             GltfWriter w;
             const float inf = std::numeric_limits<float>::infinity();
             w.scene({w.node({{"mesh", w.mesh({{"attributes", {{"POSITION", w.positions({0, 0, 0, inf, 0, 0, 0, 1, 0})}}}})}})});
             return bytesOf(w.text());
         }});
    add({"translation_1e309", 34, Expect::Reject, "number overflow parsing '1e309'", [](const fs::path &) {
             GltfWriter w = triangleFile();
             w.doc["nodes"][0]["translation"] = {12345.5, 0.0, 0.0};
             return bytesOf(replaceOnce(w.text(), "12345.5", "1e309"));
         }});
    add(triangleCase("matrix_projective_bottom_row", 34, Expect::Reject, "bottom row", [](GltfWriter &w) {
        w.doc["nodes"][0]["matrix"] = {1.0, 0.0, 0.0, 0.5, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    }));
    add(triangleCase("matrix_with_shear", 34, Expect::LoadWithWarning, "shear", [](GltfWriter &w) {
        w.doc["nodes"][0]["matrix"] = {1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    }));
    add(triangleCase("matrix_wrong_length", 34, Expect::Reject, "matrix has 15 numbers, expected 16",
                     [](GltfWriter &w) {
                         w.doc["nodes"][0]["matrix"] = json::array();
                         for (int i = 0; i < 15; ++i) w.doc["nodes"][0]["matrix"].push_back(i % 5 == 0 ? 1.0 : 0.0);
                     }));
    add(triangleCase("quaternion_non_unit", 34, Expect::LoadWithWarning, "normalised", [](GltfWriter &w) {
        w.doc["nodes"][0]["rotation"] = {0.0, 0.0, 0.0, 2.0}; // identity, twice too long
    }));
    HostileFile nonUnit = files.back(); // the geometry must be the normalised rotation's
    nonUnit.name = "quaternion_non_unit_is_normalised";
    nonUnit.checkScene = expectUnitTriangle;
    add(nonUnit);
    add(triangleCase("quaternion_zero", 34, Expect::Reject, "zero rotation quaternion",
                     [](GltfWriter &w) { w.doc["nodes"][0]["rotation"] = {0.0, 0.0, 0.0, 0.0}; }));
    add(triangleCase("scale_product_overflows", 34, Expect::Reject, "non-finite world transform", [](GltfWriter &w) {
        w.doc["nodes"][0]["scale"] = {1e300, 1e300, 1e300};
        w.doc["nodes"][0]["children"] = {1};
        w.node({{"scale", {1e300, 1e300, 1e300}}, {"mesh", 0}});
    }));

    // ---- 35. Graph and JSON bombs (the 10^5-deep node chain is a test of its own below).
    add(triangleCase("node_cycle", 35, Expect::Reject, "cycle", [](GltfWriter &w) {
        w.doc["nodes"][0]["children"] = {1};
        w.node({{"children", {0}}});
        w.doc["scenes"][0]["nodes"] = json::array();
    }));
    add(triangleCase("node_is_its_own_child", 35, Expect::Reject, "cycle",
                     [](GltfWriter &w) { w.doc["nodes"][0]["children"] = {0}; }));
    add(triangleCase("node_with_two_parents", 35, Expect::Reject,
                     "node 2 has two parents (node 0 'TriNode' and node 1)", [](GltfWriter &w) {
                         w.doc["nodes"][0]["children"] = {2};
                         w.node({{"children", {2}}});
                         w.node({{"mesh", 0}});
                     }));
    add(triangleCase("child_listed_twice", 35, Expect::Reject, "listed twice", [](GltfWriter &w) {
        w.doc["nodes"][0]["children"] = {1, 1};
        w.node({{"mesh", 0}});
    }));
    add(triangleCase("scene_root_is_a_child", 35, Expect::Reject, "as a root, but it is a child", [](GltfWriter &w) {
        w.doc["nodes"][0]["children"] = {1};
        w.node({{"mesh", 0}});
        w.doc["scenes"][0]["nodes"] = {0, 1};
    }));
    add(triangleCase("child_index_out_of_range", 35, Expect::Reject, "has child 7",
                     [](GltfWriter &w) { w.doc["nodes"][0]["children"] = {7}; }));
    for (const char *brackets : {"[]", "{}"}) {
        const std::string kind = brackets[0] == '[' ? "arrays" : "objects";
        add({"json_" + kind + "_nested_1e5_deep", 35, Expect::Reject, "nested more than 512 levels deep",
             [brackets](const fs::path &) {
                 std::string open, close;
                 for (int i = 0; i < 100000; ++i) {
                     open += brackets[0] == '[' ? "[" : "{\"a\":";
                     close += brackets[1];
                 }
                 // An object needs a value at the bottom.
                 const std::string deep = open + (brackets[0] == '[' ? "" : "0") + close;
                 std::string text = triangleFile().text();
                 return bytesOf(text.insert(text.size() - 1, ",\"extras\":" + deep));
             }});
    }
    add({"json_brackets_inside_strings_load", 35, Expect::Load, "", [](const fs::path &) {
             GltfWriter w = triangleFile();
             w.doc["nodes"][0]["name"] = std::string(100000, '[') + "\\\"{";
             return bytesOf(w.text());
         }});
    add({"glb_json_nested_1e5_deep", 35, Expect::Reject, "nested more than 512 levels deep", [](const fs::path &) {
             GltfWriter w = triangleFile();
             w.doc["extras"] = json::array();
             Bytes glb = w.glb();
             // Turn the (4-byte padded) JSON chunk's trailing spaces and the extras "[]" into
             // deep brackets of the same total length, keeping every chunk length valid.
             const std::uint32_t jsonLength = get32(glb, 12);
             std::string json(glb.begin() + 20, glb.begin() + 20 + jsonLength);
             const std::size_t at = json.find("\"extras\":[]") + 9;
             const std::string deep = std::string(50000, '[') + std::string(50000, ']');
             json.replace(at, 2, deep);
             while (json.size() % 4) json += ' ';
             Bytes out(glb.begin(), glb.begin() + 12);
             const Bytes tail(glb.begin() + 20 + jsonLength, glb.end());
             Bytes header(8);
             put32(header, 0, std::uint32_t(json.size()));
             put32(header, 4, 0x4E4F534Au);
             out.insert(out.end(), header.begin(), header.end());
             out.insert(out.end(), json.begin(), json.end());
             out.insert(out.end(), tail.begin(), tail.end());
             put32(out, 8, std::uint32_t(out.size()));
             return out;
         }, {}, ".glb"});

    // ---- 36. Resources: external files, data URIs, GLB containers.
    add({"missing_bin", 36, Expect::Reject, "missing.bin",
         [](const fs::path &) { return bytesOf(triangleFile().text("missing.bin")); }});
    add({"bin_shorter_than_byteLength", 36, Expect::Reject, "short.bin", [](const fs::path &folder) {
             const GltfWriter w = triangleFile();
             writeFile(folder / "short.bin", Bytes(w.bin.begin(), w.bin.end() - 4));
             return bytesOf(w.text("short.bin"));
         }});
    add({"external_bin_inside_folder_loads", 36, Expect::Load, "", [](const fs::path &folder) {
             const GltfWriter w = triangleFile();
             fs::create_directories(folder / "sub");
             writeFile(folder / "sub" / "tri.bin", w.bin);
             return bytesOf(w.text("sub/tri.bin"));
         }, expectUnitTriangle});
    add(uriCase("uri_dot_dot", "../secret.bin", "leaves the asset's folder"));
    add(uriCase("uri_dot_dot_inside", "sub/../../secret.bin", "leaves the asset's folder"));
    add(uriCase("uri_percent_encoded_dot_dot", "%2e%2e/secret.bin", "leaves the asset's folder"));
    add(uriCase("uri_backslash_dot_dot", "..\\secret.bin", "leaves the asset's folder"));
    add(uriCase("uri_file_url", "file:///etc/passwd", "URL"));
    add(uriCase("uri_http_url", "http://example.com/tri.bin", "URL"));
    add(uriCase("uri_windows_drive", "C:\\Windows\\win.ini", "absolute path"));
    add({"uri_absolute_path", 36, Expect::Reject, "absolute path", [](const fs::path &folder) {
             // The file exists and is valid: only the spelling of its uri is wrong.
             return bytesOf(triangleFile().text(fs::absolute(folder.parent_path() / "secret.bin").string()));
         }});
    add({"uri_symlink_leading_outside", 36, Expect::Reject, "resolves outside the asset's folder",
         [](const fs::path &folder) {
             std::error_code ec;
             fs::create_symlink(folder.parent_path() / "secret.bin", folder / "link.bin", ec);
             return bytesOf(triangleFile().text("link.bin"));
         }});
    // Shell syntax must stay text: tinygltf < 2.6.3 passed uris to wordexp() (issue #368).
    add(uriCase("uri_backticks", "`touch pwned`.bin", "touch pwned"));
    add(uriCase("uri_dollar_parentheses", "$(touch pwned).bin", "touch pwned"));
    add(uriCase("uri_tilde", "~/tri.bin", "tri.bin"));
    add({"uri_is_a_directory", 36, Expect::Reject, "sub", [](const fs::path &folder) {
             fs::create_directories(folder / "sub");
             return bytesOf(triangleFile().text("sub"));
         }});
    add({"data_uri_invalid_base64", 36, Expect::Reject, "Failed to decode 'uri'", [](const fs::path &) {
             return bytesOf(triangleFile().text("data:application/octet-stream;base64,@@@@!!!!"));
         }});
    add({"data_uri_shorter_than_byteLength", 36, Expect::Reject, "Failed to decode 'uri'", [](const fs::path &) {
             GltfWriter w = triangleFile();
             const std::string full = "data:application/octet-stream;base64," + base64(w.bin);
             std::vector<std::uint8_t> shorter(w.bin.begin(), w.bin.end() - 12);
             return bytesOf(replaceOnce(w.text(), full, "data:application/octet-stream;base64," + base64(shorter)));
         }});
    add({"data_uri_not_base64", 36, Expect::Reject, "percent-encoded data URI holds 5 bytes, fewer than its byteLength 36",
         [](const fs::path &) {
             return bytesOf(triangleFile().text("data:application/octet-stream,plain"));
         }});
    add({"image_uri_outside_folder", 36, Expect::Reject, "leaves the asset's folder", [](const fs::path &) {
             GltfWriter w = triangleFile();
             w.doc["images"] = json::array({{{"uri", "../secret.png"}}});
             return bytesOf(w.text());
         }});
    add(glbCase("glb_valid", Expect::Load, "", [](Bytes &) {}));
    files.back().checkScene = expectUnitTriangle;
    for (std::size_t cut : {std::size_t(4), std::size_t(19), std::size_t(40)})
        add(glbCase("glb_truncated_to_" + std::to_string(cut) + "_bytes", Expect::Reject, "", [cut](Bytes &b) {
            b.resize(cut);
        }));
    add(glbCase("glb_truncated_by_1_byte", Expect::Reject, "truncated", [](Bytes &b) { b.pop_back(); }));
    add(glbCase("glb_json_chunk_length_unaligned", Expect::Reject, "not a multiple of 4", [](Bytes &b) {
        // One JSON padding space fewer: the BIN chunk then starts at an unaligned offset.
        const std::uint32_t jsonLength = get32(b, 12);
        b.erase(b.begin() + 20 + jsonLength - 1);
        put32(b, 12, jsonLength - 1);
        put32(b, 8, std::uint32_t(b.size()));
    }));
    add(glbCase("glb_bin_chunk_past_end", Expect::Reject, "runs past the end of the file", [](Bytes &b) {
        const std::size_t binHeader = 20 + get32(b, 12);
        put32(b, binHeader, get32(b, binHeader) + 8);
    }));
    add(glbCase("glb_bin_chunk_length_2pow32_minus_1", Expect::Reject, "runs past the end of the file",
                [](Bytes &b) { put32(b, 20 + get32(b, 12), 0xffffffffu); }));
    add(glbCase("glb_json_chunk_length_2pow32_minus_1", Expect::Reject, "does not fit in the file",
                [](Bytes &b) { put32(b, 12, 0xffffffffu); }));
    add(glbCase("glb_version_1", Expect::Reject, "GLB version is 1", [](Bytes &b) { put32(b, 4, 1); }));
    add(glbCase("glb_first_chunk_not_json", Expect::Reject, "first chunk is not JSON",
                [](Bytes &b) { put32(b, 16, 0x004E4942u); }));
    add(glbCase("glb_buffer_longer_than_bin_chunk", Expect::Reject, "binary size", [](Bytes &b) {
        // Rewrite "byteLength":36 of the buffer (the last one in the JSON) as 40, same length.
        std::string json(b.begin() + 20, b.begin() + 20 + get32(b, 12));
        const std::size_t at = json.rfind("\"byteLength\":36");
        ASSERT_NE(at, std::string::npos);
        json.replace(at, 15, "\"byteLength\":40");
        std::copy(json.begin(), json.end(), b.begin() + 20);
    }));
    return files;
}

/// A private folder per test process, removed when the process ends.
fs::path hostileRoot() {
    struct Root {
        fs::path path = fs::temp_directory_path() / ("mvcl-hostile-files-" + std::to_string(::getpid()));
        Root() {
            fs::remove_all(path);
            fs::create_directories(path);
            // A valid buffer just outside every case's folder: escaping uris would find it.
            writeFile(path / "secret.bin", triangleFile().bin);
        }
        ~Root() {
            std::error_code ec;
            fs::remove_all(path, ec);
        }
    };
    static const Root root;
    return root.path;
}

class GltfHostileFile : public ::testing::TestWithParam<HostileFile> {};

TEST_P(GltfHostileFile, CleanErrorOrSceneNeverACrash) {
    const HostileFile &f = GetParam();
    const fs::path folder = hostileRoot() / f.name;
    fs::remove_all(folder);
    fs::create_directories(folder);
    const fs::path path = folder / (f.name + f.extension);
    writeFile(path, f.make(folder));

    std::string error, problem;
    Scene scene;
    try {
        scene = loadGltf(path);
    } catch (const Error &e) {
        error = e.what();
        problem = e.problem(); // the fragment must be in the problem, not just in the file's name
    }
    if (f.expect == Expect::Reject) {
        ASSERT_FALSE(error.empty()) << f.name << " loaded but must be rejected";
        EXPECT_NE(error.find(path.filename().string()), std::string::npos) << "error does not name the file: " << error;
        EXPECT_NE(problem.find(f.fragment), std::string::npos) << "error does not say '" << f.fragment << "': " << error;
        std::cout << "  [rejected] " << error << "\n";
    } else {
        ASSERT_TRUE(error.empty()) << error;
        EXPECT_FALSE(scene.materials.empty());
        if (f.expect == Expect::LoadWithWarning) {
            const auto &w = scene.report.warnings;
            EXPECT_TRUE(std::any_of(w.begin(), w.end(), [&](const std::string &m) { return m.find(f.fragment) != std::string::npos; }))
                << "no warning says '" << f.fragment << "'";
        }
        if (f.checkScene) f.checkScene(scene);
    }
    // Nothing from the file was ever executed.
    EXPECT_FALSE(fs::exists(folder / "pwned"));
    EXPECT_FALSE(fs::exists("pwned"));
}

INSTANTIATE_TEST_SUITE_P(CatalogueD, GltfHostileFile, ::testing::ValuesIn(hostileFiles()),
                         [](const ::testing::TestParamInfo<HostileFile> &info) { return info.param.name; });

TEST(GltfHostileFiles, EveryCatalogueCaseHasFilesAndBothOutcomesOccur) {
    std::map<int, int> perCase;
    int rejected = 0, loaded = 0;
    for (const HostileFile &f : hostileFiles()) {
        ++perCase[f.catalogueCase];
        (f.expect == Expect::Reject ? rejected : loaded) += 1;
    }
    for (int c : {30, 31, 32, 34, 35, 36}) EXPECT_GE(perCase[c], 3) << "catalogue case " << c;
    EXPECT_GT(rejected, 0);
    EXPECT_GT(loaded, 0);
    std::cout << "  hostile files: " << rejected << " must be rejected, " << loaded << " must load\n";
}

// ---- 33. Primitive modes 0–6 × index types: points and lines skipped with a warning; strips and
// fans triangulated with their winding kept (every triangle faces +Z here).

struct ModeCase {
    int mode;
    int indexType; ///< 5121, 5123, 5125, or 0 for no indices (vertices in sequence order)
};

class GltfPrimitiveMode : public ::testing::TestWithParam<ModeCase> {};

TEST_P(GltfPrimitiveMode, SkippedOrTriangulatedWithWinding) {
    const auto [mode, indexType] = GetParam();
    // Grid vertices 0:(0,0) 1:(0,1) 2:(1,0) 3:(1,1) 4:(2,0) 5:(2,1), and for each mode a sequence
    // whose triangles are all counter-clockwise seen from +Z.
    const std::vector<glm::vec2> grid = {{0, 0}, {0, 1}, {1, 0}, {1, 1}, {2, 0}, {2, 1}};
    std::vector<std::uint32_t> sequence;
    std::size_t expectedTriangles = 0;
    switch (mode) {
    case 4:
        sequence = {0, 2, 1, 2, 3, 1};
        expectedTriangles = 2;
        break;
    case 5:
        sequence = {1, 0, 3, 2, 5, 4};
        expectedTriangles = 4;
        break;
    case 6:
        sequence = {0, 2, 3, 1};
        expectedTriangles = 2;
        break;
    default: sequence = {0, 1, 2, 3}; // points, lines, line loop, line strip
    }
    GltfWriter w;
    json primitive = {{"mode", mode}};
    if (indexType == 0) {
        std::vector<float> xyz;
        for (std::uint32_t v : sequence) xyz.insert(xyz.end(), {grid[v].x, grid[v].y, 0.f});
        primitive["attributes"]["POSITION"] = w.positions(xyz);
    } else {
        std::vector<float> xyz;
        for (const glm::vec2 &p : grid) xyz.insert(xyz.end(), {p.x, p.y, 0.f});
        primitive["attributes"]["POSITION"] = w.positions(xyz);
        primitive["indices"] = indexType == 5121   ? w.indices8({sequence.begin(), sequence.end()})
                               : indexType == 5123 ? w.indices16({sequence.begin(), sequence.end()})
                                                   : w.indices32(sequence);
    }
    w.scene({w.node({{"mesh", w.mesh(primitive)}})});
    const Scene s = w.load();
    ASSERT_EQ(s.triangleCount(), expectedTriangles);
    if (expectedTriangles == 0) {
        EXPECT_EQ(s.report.primitivesSkipped, 1u);
        const auto &warnings = s.report.warnings;
        EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(),
                                [](const std::string &m) { return m.find("skipped") != std::string::npos; }));
        return;
    }
    const TriangleMesh &m = s.meshes.at(0);
    for (std::size_t t = 0; t < m.indices.size(); ++t) {
        const glm::uvec3 i = m.indices[t];
        const glm::vec3 n = glm::cross(m.positions[i.y] - m.positions[i.x], m.positions[i.z] - m.positions[i.x]);
        EXPECT_GT(n.z, 0.f) << "triangle " << t << " is clockwise";
    }
}

std::vector<ModeCase> allModes() {
    std::vector<ModeCase> cases;
    for (int mode = 0; mode <= 6; ++mode)
        for (int type : {0, 5121, 5123, 5125}) cases.push_back({mode, type});
    return cases;
}

std::string modeCaseName(const ::testing::TestParamInfo<ModeCase> &info) {
    static const char *kModes[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP",
                                   "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
    const int t = info.param.indexType;
    return std::string(kModes[info.param.mode]) + "_" +
           (t == 0 ? "unindexed" : t == 5121 ? "u8" : t == 5123 ? "u16" : "u32");
}

INSTANTIATE_TEST_SUITE_P(Catalogue33, GltfPrimitiveMode, ::testing::ValuesIn(allModes()), modeCaseName);

// ---- 35. A 10^5-deep node chain loads (composed in double, no recursion); closed, it is a cycle.

TEST(GltfHostileFiles, HundredThousandDeepNodeChainDoesNotOverflowTheStack) {
    GltfWriter w = triangleFile();
    constexpr int kDepth = 100000;
    json nodes = json::array();
    for (int i = 0; i < kDepth; ++i) {
        json n = {{"translation", {0.001, 0.0, 0.0}}};
        if (i + 1 < kDepth) n["children"] = {i + 1};
        else n["mesh"] = 0;
        nodes.push_back(n);
    }
    w.doc["nodes"] = nodes;
    w.scene({0});
    const Scene s = w.load();
    ASSERT_EQ(s.triangleCount(), 1u);
    const double x = double(s.bounds().min.x) + s.worldOrigin.x;
    EXPECT_NEAR(x, 100.0, 1e-6); // composed in double: 10^5 · 0.001

    w.doc["nodes"][kDepth - 1]["children"] = {0};
    w.doc["scenes"][0]["nodes"] = json::array();
    try {
        w.load();
        FAIL() << "a 10^5-node cycle loaded";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("cycle"), std::string::npos) << e.what();
    }
}

// ---- Limits and plain garbage.

TEST(GltfHostileFiles, OversizeEmptyAndGarbageRejected) {
    const std::string text = triangleFile().text();
    GltfLoadOptions small;
    small.maxFileBytes = 16;
    EXPECT_THROW(loadGltfFromMemory(asBytes(text), "big.gltf", "", small), Error);
    EXPECT_THROW(loadGltfFromMemory({}, "empty.gltf", ""), Error);
    const std::string garbage = "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": 7";
    EXPECT_THROW(loadGltfFromMemory(asBytes(garbage), "garbage.gltf", ""), Error);
    EXPECT_THROW(loadGltf(fs::path(MVCL_TEST_DATA_DIR) / "models" / "does-not-exist.glb"), Error);
}

TEST(GltfHostileFiles, RequiredDracoRejectedByName) {
    GltfWriter w = triangleFile();
    w.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    w.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    try {
        w.load();
        FAIL() << "a file requiring Draco loaded";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("KHR_draco_mesh_compression"), std::string::npos) << e.what();
    }
}

TEST(GltfHostileFiles, EveryTruncationOfARealGlbIsRejectedCleanly) {
    std::ifstream in(fs::path(MVCL_TEST_DATA_DIR) / "models" / "Box" / "Box.glb", std::ios::binary);
    const Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 100u);
    EXPECT_EQ(loadGltfFromMemory(bytes, "Box.glb", "").triangleCount(), 12u);
    for (std::size_t cut = 0; cut < bytes.size(); ++cut)
        EXPECT_THROW(loadGltfFromMemory({bytes.data(), cut}, "Box.glb", ""), Error) << "cut at " << cut;
}

} // namespace
