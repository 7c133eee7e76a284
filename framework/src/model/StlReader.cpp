// STL, binary and ASCII. STL stores every triangle with its own three corners, so corners are
// welded by exact position (bit for bit) into an indexed mesh: shared edges make closed meshes
// recognisable (clip caps) and let layer inference see solids. Facet normals are not read: many
// writers leave them zero, and the winding says the same.

#include "MeshFileData_p.h"
#include "TextCursor_p.h"

#include <glm/geometric.hpp>

#include <bit>
#include <cstring>

namespace mvcl::meshfile {

namespace {

constexpr std::size_t kBinaryHeaderBytes = 84; // 80-byte comment, then a uint32 triangle count
constexpr std::size_t kBinaryTriangleBytes = 50; // normal, three corners (float32 × 12), uint16 attribute

/// Corners → indexed vertices, by exact position: an open-addressing table over the bit
/// patterns (−0 folded into +0), so a million triangles weld in one pass without a node-based map.
class CornerWelder {
public:
    CornerWelder(MeshPart &part, std::size_t expectedCorners) : m_part(part) {
        std::size_t size = 16;
        while (size < 2 * expectedCorners) size *= 2;
        m_slots.assign(size, kEmpty);
        m_part.positions.reserve(expectedCorners / 4);
    }

    std::uint32_t add(glm::dvec3 p) {
        p += glm::dvec3(0.0); // −0 + 0 = +0: one key for both zeros
        if (m_part.positions.size() * 2 >= m_slots.size()) grow();
        std::size_t slot = hash(p) & (m_slots.size() - 1);
        while (m_slots[slot] != kEmpty) {
            if (m_part.positions[m_slots[slot]] == p) return m_slots[slot];
            slot = (slot + 1) & (m_slots.size() - 1);
        }
        m_slots[slot] = std::uint32_t(m_part.positions.size());
        m_part.positions.push_back(p);
        return m_slots[slot];
    }

private:
    static constexpr std::uint32_t kEmpty = 0xffffffffu;

    static std::size_t hash(const glm::dvec3 &p) {
        std::uint64_t h = 0x9e3779b97f4a7c15ull;
        for (int k = 0; k < 3; ++k) {
            h ^= std::bit_cast<std::uint64_t>(p[k]);
            h *= 0xff51afd7ed558ccdull;
            h ^= h >> 32;
        }
        return std::size_t(h);
    }

    void grow() {
        std::vector<std::uint32_t> slots(m_slots.size() * 2, kEmpty);
        for (std::uint32_t i = 0; i < m_part.positions.size(); ++i) {
            std::size_t slot = hash(m_part.positions[i]) & (slots.size() - 1);
            while (slots[slot] != kEmpty) slot = (slot + 1) & (slots.size() - 1);
            slots[slot] = i;
        }
        m_slots.swap(slots);
    }

    MeshPart &m_part;
    std::vector<std::uint32_t> m_slots;
};

void addTriangle(const ReadInput &input, MeshPart &part, CornerWelder &welder, const glm::dvec3 (&corners)[3]) {
    for (const glm::dvec3 &c : corners)
        if (!isFinite(c))
            fail(input, "triangle " + std::to_string(part.triangles.size()) + " has a corner that is not finite (" +
                            std::to_string(c.x) + ", " + std::to_string(c.y) + ", " + std::to_string(c.z) + ")");
    checkTriangleCount(input, part.triangles.size() + 1);
    part.triangles.emplace_back(welder.add(corners[0]), welder.add(corners[1]), welder.add(corners[2]));
}

float readFloat(const std::uint8_t *p) {
    // STL is little-endian, as is every machine mvcl is built for (checked below).
    float f;
    std::memcpy(&f, p, sizeof f);
    return f;
}
static_assert(std::endian::native == std::endian::little, "the binary STL reader assumes a little-endian host");

MeshFileData readBinary(const ReadInput &input) {
    const std::span<const std::uint8_t> bytes = input.bytes;
    std::uint32_t count;
    std::memcpy(&count, bytes.data() + 80, sizeof count);
    const std::uint64_t expected = kBinaryHeaderBytes + std::uint64_t(count) * kBinaryTriangleBytes;
    if (expected != bytes.size())
        fail(input, "binary STL header says " + std::to_string(count) + " triangles (" + std::to_string(expected) +
                        " bytes) but the file has " + std::to_string(bytes.size()) +
                        " bytes: truncated, or not an STL file");
    if (count == 0) fail(input, "the STL file holds no triangles");
    checkTriangleCount(input, count);
    MeshFileData data;
    MeshPart &part = data.parts.emplace_back();
    part.triangles.reserve(count);
    CornerWelder welder(part, std::size_t(count) * 3);
    for (std::uint32_t t = 0; t < count; ++t) {
        const std::uint8_t *facet = bytes.data() + kBinaryHeaderBytes + std::size_t(t) * kBinaryTriangleBytes;
        glm::dvec3 corners[3];
        for (int c = 0; c < 3; ++c) {
            const std::uint8_t *p = facet + 12 + 12 * c;
            corners[c] = glm::dvec3(readFloat(p), readFloat(p + 4), readFloat(p + 8));
        }
        addTriangle(input, part, welder, corners);
    }
    return data;
}

MeshFileData readAscii(const ReadInput &input) {
    TextCursor text(input);
    MeshFileData data;
    while (text.skipSpace()) {
        text.expectWord("solid");
        MeshPart &part = data.parts.emplace_back();
        part.name = text.restOfLine();
        CornerWelder welder(part, std::min<std::size_t>(input.bytes.size() / 40, std::size_t(1) << 24));
        for (;;) {
            const std::string_view word = text.word();
            if (word == "endsolid") {
                text.restOfLine();
                break;
            }
            if (word != "facet") text.failAt("expected 'facet' or 'endsolid', found '" + std::string(word) + "'");
            text.expectWord("normal");
            for (int k = 0; k < 3; ++k) text.number(); // facet normals are not used (see the top)
            text.expectWord("outer");
            text.expectWord("loop");
            std::vector<glm::dvec3> loop;
            while (text.peekWord() == "vertex") {
                text.word();
                glm::dvec3 v;
                for (int k = 0; k < 3; ++k) v[k] = text.number();
                loop.push_back(v);
            }
            text.expectWord("endloop");
            text.expectWord("endfacet");
            if (loop.size() < 3) text.failAt("a facet has " + std::to_string(loop.size()) + " vertices");
            for (std::size_t i = 1; i + 1 < loop.size(); ++i) addTriangle(input, part, welder, {loop[0], loop[i], loop[i + 1]});
        }
    }
    if (data.parts.empty()) fail(input, "the STL file holds no solid");
    return data;
}

} // namespace

MeshFileData readStl(const ReadInput &input) {
    const std::span<const std::uint8_t> bytes = input.bytes;
    if (bytes.size() >= kBinaryHeaderBytes) {
        std::uint32_t count;
        std::memcpy(&count, bytes.data() + 80, sizeof count);
        // Binary files often begin with "solid" too; the size decides.
        if (kBinaryHeaderBytes + std::uint64_t(count) * kBinaryTriangleBytes == bytes.size()) return readBinary(input);
    }
    if (looksLikeText(bytes) && startsWithWord(bytes, "solid")) return readAscii(input);
    if (bytes.size() < kBinaryHeaderBytes)
        fail(input, "too short for a binary STL file (" + std::to_string(bytes.size()) + " bytes) and not an ASCII one");
    return readBinary(input); // fails with the count against the size
}

} // namespace mvcl::meshfile
