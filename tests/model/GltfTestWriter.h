#pragma once
/// \file GltfTestWriter.h
/// A tiny glTF writer for the loader tests: builds hostile and corner-case files in memory, with
/// one buffer embedded as a data URI (or written next to the file, or packed into a GLB).

#include <mvcl/model/GltfLoader.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace mvcl::test {

inline std::string base64(const std::vector<std::uint8_t> &data) {
    static const char *kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < data.size(); i += 3) {
        const std::uint32_t v = std::uint32_t(data[i]) << 16 | std::uint32_t(data[i + 1]) << 8 | data[i + 2];
        for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
    }
    if (i + 1 == data.size()) {
        const std::uint32_t v = std::uint32_t(data[i]) << 16;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == data.size()) {
        const std::uint32_t v = std::uint32_t(data[i]) << 16 | std::uint32_t(data[i + 1]) << 8;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

inline std::span<const std::uint8_t> asBytes(const std::string &text) {
    return {reinterpret_cast<const std::uint8_t *>(text.data()), text.size()};
}

struct GltfWriter {
    std::vector<std::uint8_t> bin;
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};

    template <typename T> std::size_t append(const std::vector<T> &values) {
        while (bin.size() % 4) bin.push_back(0);
        const std::size_t offset = bin.size();
        bin.resize(offset + values.size() * sizeof(T));
        if (!values.empty()) std::memcpy(bin.data() + offset, values.data(), values.size() * sizeof(T));
        return offset;
    }
    /// Adds a bufferView over `values` and returns its index.
    template <typename T> int view(const std::vector<T> &values, int stride = 0) {
        const std::size_t offset = append(values);
        nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}};
        if (stride) v["byteStride"] = stride;
        doc["bufferViews"].push_back(v);
        return int(doc["bufferViews"].size()) - 1;
    }
    int accessor(int bufferView, int componentType, std::uint64_t count, const char *type) {
        nlohmann::json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
        if (bufferView >= 0) a["bufferView"] = bufferView;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }
    int positions(const std::vector<float> &xyz) { return accessor(view(xyz), 5126, xyz.size() / 3, "VEC3"); }
    int indices8(const std::vector<std::uint8_t> &idx) { return accessor(view(idx), 5121, idx.size(), "SCALAR"); }
    int indices16(const std::vector<std::uint16_t> &idx) { return accessor(view(idx), 5123, idx.size(), "SCALAR"); }
    int indices32(const std::vector<std::uint32_t> &idx) { return accessor(view(idx), 5125, idx.size(), "SCALAR"); }
    /// A mesh with one primitive; returns the mesh index.
    int mesh(nlohmann::json primitive, const std::string &name = "") {
        nlohmann::json m = {{"primitives", nlohmann::json::array({primitive})}};
        if (!name.empty()) m["name"] = name;
        doc["meshes"].push_back(m);
        return int(doc["meshes"].size()) - 1;
    }
    int node(nlohmann::json n) {
        doc["nodes"].push_back(n);
        return int(doc["nodes"].size()) - 1;
    }
    void scene(std::vector<int> roots) {
        doc["scenes"] = nlohmann::json::array({{{"nodes", roots}}});
        doc["scene"] = 0;
    }

    /// The .gltf text; the buffer is a data URI unless `bufferUri` names an external file.
    std::string text(const std::string &bufferUri = "") const {
        nlohmann::json d = doc;
        if (!bin.empty())
            d["buffers"] = nlohmann::json::array(
                {{{"byteLength", bin.size()},
                  {"uri", bufferUri.empty() ? "data:application/octet-stream;base64," + base64(bin) : bufferUri}}});
        return d.dump();
    }
    /// The same file as a GLB: JSON chunk, then the buffer as the BIN chunk (both padded to 4).
    std::vector<std::uint8_t> glb() const {
        nlohmann::json d = doc;
        if (!bin.empty()) d["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
        std::string json = d.dump();
        while (json.size() % 4) json += ' ';
        std::vector<std::uint8_t> chunkBin = bin;
        while (chunkBin.size() % 4) chunkBin.push_back(0);
        std::vector<std::uint8_t> out;
        const auto put32 = [&](std::uint32_t v) {
            for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
        };
        const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + chunkBin.size());
        put32(0x46546C67u); // "glTF"
        put32(2);
        put32(std::uint32_t(total));
        put32(std::uint32_t(json.size()));
        put32(0x4E4F534Au); // "JSON"
        out.insert(out.end(), json.begin(), json.end());
        if (!bin.empty()) {
            put32(std::uint32_t(chunkBin.size()));
            put32(0x004E4942u); // "BIN\0"
            out.insert(out.end(), chunkBin.begin(), chunkBin.end());
        }
        return out;
    }
    Scene load(const GltfLoadOptions &options = {}) const {
        const std::string t = text();
        return loadGltfFromMemory(asBytes(t), "synthetic.gltf", std::filesystem::temp_directory_path(), options);
    }
};

/// One triangle in the XY plane, counter-clockwise seen from +Z.
inline GltfWriter triangleFile(const std::string &meshName = "Tri") {
    GltfWriter w;
    const int pos = w.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int m = w.mesh({{"attributes", {{"POSITION", pos}}}}, meshName);
    w.scene({w.node({{"mesh", m}, {"name", "TriNode"}})});
    return w;
}

} // namespace mvcl::test
