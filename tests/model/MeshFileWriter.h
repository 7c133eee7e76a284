#pragma once
// Writes an indexed triangle mesh as STL (binary, ASCII), PLY (ASCII, binary either byte order)
// and OBJ, for the mesh-file loader's tests: the same geometry in every format.

#include <glm/vec3.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mvcl::test {

struct PlainMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    std::vector<glm::vec3> normals; ///< empty or one per position
    std::vector<glm::vec3> colors;  ///< empty or one per position, 0..1
};

/// A closed unit cube from `lo` to `lo + size`, counter-clockwise seen from outside.
inline PlainMesh cubeMesh(glm::vec3 lo = glm::vec3(0.f), float size = 1.f) {
    PlainMesh m;
    for (int i = 0; i < 8; ++i) m.positions.push_back(lo + size * glm::vec3(float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)));
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

inline std::string binaryStl(const PlainMesh &m) {
    std::string out(80, ' ');
    const auto put = [&out](const void *p, std::size_t n) { out.append(static_cast<const char *>(p), n); };
    const auto count = std::uint32_t(m.triangles.size());
    put(&count, 4);
    for (const glm::uvec3 &t : m.triangles) {
        const float zero[3] = {0.f, 0.f, 0.f};
        put(zero, 12);
        for (int k = 0; k < 3; ++k) put(&m.positions[t[k]], 12);
        const std::uint16_t attribute = 0;
        put(&attribute, 2);
    }
    return out;
}

inline std::string asciiStl(const PlainMesh &m, const std::string &name = "part") {
    std::ostringstream out;
    out.precision(9);
    out << "solid " << name << "\n";
    for (const glm::uvec3 &t : m.triangles) {
        out << "  facet normal 0 0 0\n    outer loop\n";
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 &p = m.positions[t[k]];
            out << "      vertex " << p.x << " " << p.y << " " << p.z << "\n";
        }
        out << "    endloop\n  endfacet\n";
    }
    out << "endsolid " << name << "\n";
    return out.str();
}

enum class PlyEncoding { Ascii, LittleEndian, BigEndian };

inline std::string ply(const PlainMesh &m, PlyEncoding encoding) {
    std::ostringstream out;
    out.precision(9);
    out << "ply\nformat "
        << (encoding == PlyEncoding::Ascii ? "ascii" : encoding == PlyEncoding::LittleEndian ? "binary_little_endian" : "binary_big_endian")
        << " 1.0\ncomment written by mvcl's tests\nelement vertex " << m.positions.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n";
    if (!m.normals.empty()) out << "property float nx\nproperty float ny\nproperty float nz\n";
    if (!m.colors.empty()) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    out << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    const auto put = [&](const auto value) {
        if (encoding == PlyEncoding::Ascii) {
            out << +value << ' ';
            return;
        }
        char raw[sizeof value];
        std::memcpy(raw, &value, sizeof value);
        if ((encoding == PlyEncoding::BigEndian) != (std::endian::native == std::endian::big))
            for (std::size_t i = 0; i < sizeof value / 2; ++i) std::swap(raw[i], raw[sizeof value - 1 - i]);
        out.write(raw, sizeof value);
    };
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        for (int k = 0; k < 3; ++k) put(m.positions[i][k]);
        if (!m.normals.empty())
            for (int k = 0; k < 3; ++k) put(m.normals[i][k]);
        if (!m.colors.empty())
            for (int k = 0; k < 3; ++k) put(std::uint8_t(m.colors[i][k] * 255.f + 0.5f));
        if (encoding == PlyEncoding::Ascii) out << '\n';
    }
    for (const glm::uvec3 &t : m.triangles) {
        put(std::uint8_t(3));
        for (int k = 0; k < 3; ++k) put(std::int32_t(t[k]));
        if (encoding == PlyEncoding::Ascii) out << '\n';
    }
    return out.str();
}

inline std::string obj(const PlainMesh &m, const std::string &group = "part") {
    std::ostringstream out;
    out.precision(9);
    for (const glm::vec3 &p : m.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
    out << "g " << group << "\n";
    for (const glm::uvec3 &t : m.triangles) out << "f " << t.x + 1 << " " << t.y + 1 << " " << t.z + 1 << "\n";
    return out.str();
}

inline void writeFile(const std::filesystem::path &path, const std::string &bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

} // namespace mvcl::test
