// PLY (Turk 1994), ASCII and binary in either byte order. The header declares elements with
// counts and typed properties; the body must hold exactly that. Counts are checked against the
// bytes left before anything is allocated, so a header that lies cannot make the reader reserve
// memory the file does not back. Vertices give x, y, z and, when present, nx, ny, nz and
// red, green, blue; faces give vertex_indices (or vertex_index) lists, split into fans.

#include "MeshFileData_p.h"
#include "TextCursor_p.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace mvcl::meshfile {

namespace {

enum class Encoding : uint8_t { Ascii, LittleEndian, BigEndian };
enum class ScalarType : uint8_t { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

std::optional<ScalarType> scalarType(std::string_view name) {
    if (name == "char" || name == "int8") return ScalarType::Int8;
    if (name == "uchar" || name == "uint8") return ScalarType::Uint8;
    if (name == "short" || name == "int16") return ScalarType::Int16;
    if (name == "ushort" || name == "uint16") return ScalarType::Uint16;
    if (name == "int" || name == "int32") return ScalarType::Int32;
    if (name == "uint" || name == "uint32") return ScalarType::Uint32;
    if (name == "float" || name == "float32") return ScalarType::Float32;
    if (name == "double" || name == "float64") return ScalarType::Float64;
    return std::nullopt;
}

std::size_t sizeOf(ScalarType t) {
    switch (t) {
    case ScalarType::Int8:
    case ScalarType::Uint8: return 1;
    case ScalarType::Int16:
    case ScalarType::Uint16: return 2;
    case ScalarType::Int32:
    case ScalarType::Uint32:
    case ScalarType::Float32: return 4;
    case ScalarType::Float64: return 8;
    }
    return 1;
}

struct Property {
    std::string name;
    ScalarType type = ScalarType::Float32;
    std::optional<ScalarType> listCount; ///< set for list properties: the type of the count
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    /// Bytes of one element in a binary file without lists (its minimum with lists).
    std::size_t minimumBytes() const {
        std::size_t n = 0;
        for (const Property &p : properties) n += p.listCount ? sizeOf(*p.listCount) : sizeOf(p.type);
        return n;
    }
};

struct Header {
    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    std::size_t bodyOffset = 0;
};

/// The largest polygon read; more corners than this is a broken or hostile file.
constexpr std::uint64_t kMaxPolygonCorners = 1u << 16;

Header readHeader(const ReadInput &input) {
    const std::string_view text(reinterpret_cast<const char *>(input.bytes.data()), input.bytes.size());
    if (!text.starts_with("ply\n") && !text.starts_with("ply\r\n")) fail(input, "not a PLY file (no 'ply' line first)");
    std::size_t end = text.find("end_header");
    if (end == std::string_view::npos) fail(input, "the PLY header has no end_header line");
    Header header;
    std::size_t bodyStart = text.find('\n', end);
    header.bodyOffset = bodyStart == std::string_view::npos ? text.size() : bodyStart + 1;

    const ReadInput headerInput{input.bytes.first(end), input.name, {}, input.limits};
    TextCursor cursor(headerInput);
    cursor.expectWord("ply");
    bool sawFormat = false;
    while (cursor.skipSpace()) {
        const std::string_view keyword = cursor.word();
        if (keyword == "comment" || keyword == "obj_info") {
            cursor.restOfLine();
        } else if (keyword == "format") {
            const std::string_view format = cursor.word();
            if (format == "ascii") header.encoding = Encoding::Ascii;
            else if (format == "binary_little_endian") header.encoding = Encoding::LittleEndian;
            else if (format == "binary_big_endian") header.encoding = Encoding::BigEndian;
            else cursor.failAt("unknown PLY format '" + std::string(format.substr(0, 40)) + "'");
            if (cursor.restOfLine() != "1.0") cursor.failAt("only PLY version 1.0 is read");
            sawFormat = true;
        } else if (keyword == "element") {
            Element &e = header.elements.emplace_back();
            e.name = std::string(cursor.word());
            e.count = cursor.count(std::uint64_t(1) << 40, "the count of element '" + e.name + "'");
        } else if (keyword == "property") {
            if (header.elements.empty()) cursor.failAt("a property before any element");
            Property p;
            const std::string_view type = cursor.word();
            if (type == "list") {
                p.listCount = scalarType(cursor.word());
                if (!p.listCount || *p.listCount == ScalarType::Float32 || *p.listCount == ScalarType::Float64)
                    cursor.failAt("a list count must have an integer type");
            }
            const std::string_view valueType = p.listCount ? cursor.word() : type;
            const std::optional<ScalarType> t = scalarType(valueType);
            if (!t) cursor.failAt("unknown property type '" + std::string(valueType.substr(0, 40)) + "'");
            p.type = *t;
            p.name = std::string(cursor.word());
            header.elements.back().properties.push_back(p);
        } else {
            cursor.failAt("unknown header keyword '" + std::string(keyword.substr(0, 40)) + "'");
        }
    }
    if (!sawFormat) fail(input, "the PLY header has no format line");
    return header;
}

/// Values of the body, one at a time, in the file's encoding.
class BodyReader {
public:
    BodyReader(const ReadInput &input, const Header &header)
        : m_input(input), m_encoding(header.encoding), m_pos(header.bodyOffset), m_text(input, header.bodyOffset) {}

    /// Starts element `index` of `counted` ("12 faces"), for the errors about it. An ASCII element
    /// is one line: a header that lies about counts shows as a line too short or too long.
    void beginElement(const std::string &counted, const std::string &name, std::uint64_t index) {
        m_counted = &counted;
        m_name = &name;
        m_index = index;
        if (m_encoding == Encoding::Ascii && !m_text.skipSpace()) failEnded();
    }
    void endElement() {
        if (m_encoding == Encoding::Ascii && m_text.skipSpaceOnLine())
            m_text.failAt(*m_name + " " + std::to_string(m_index) + " has more values than the header declares");
    }

    double scalar(ScalarType type) {
        if (m_encoding == Encoding::Ascii) {
            if (!m_text.skipSpaceOnLine())
                m_text.failAt(*m_name + " " + std::to_string(m_index) + " has fewer values than the header declares");
            return m_text.number();
        }
        const std::size_t n = sizeOf(type);
        if (m_input.bytes.size() - m_pos < n) failEnded();
        std::uint8_t raw[8];
        std::memcpy(raw, m_input.bytes.data() + m_pos, n);
        m_pos += n;
        if ((m_encoding == Encoding::BigEndian) != (std::endian::native == std::endian::big))
            for (std::size_t i = 0; i < n / 2; ++i) std::swap(raw[i], raw[n - 1 - i]);
        switch (type) {
        case ScalarType::Int8: return double(std::int8_t(raw[0]));
        case ScalarType::Uint8: return double(raw[0]);
        case ScalarType::Int16: return double(load<std::int16_t>(raw));
        case ScalarType::Uint16: return double(load<std::uint16_t>(raw));
        case ScalarType::Int32: return double(load<std::int32_t>(raw));
        case ScalarType::Uint32: return double(load<std::uint32_t>(raw));
        case ScalarType::Float32: return double(load<float>(raw));
        case ScalarType::Float64: return load<double>(raw);
        }
        return 0.0;
    }

    /// Whether `count` more elements of `properties` values and at least `bytesEach` bytes
    /// (binary) can still be in the file; an ASCII value takes two bytes at least ("0 ").
    bool canHold(std::uint64_t count, std::size_t properties, std::size_t bytesEach) {
        if (m_encoding == Encoding::Ascii) return count <= m_text.remaining() / (2 * std::max<std::size_t>(properties, 1));
        return bytesEach == 0 || count <= (m_input.bytes.size() - m_pos) / bytesEach;
    }
    bool atEnd() { return m_encoding == Encoding::Ascii ? !m_text.skipSpace() : m_pos == m_input.bytes.size(); }
    std::size_t bytesLeft() { return m_encoding == Encoding::Ascii ? (m_text.skipSpace() ? m_text.remaining() : 0) : m_input.bytes.size() - m_pos; }

private:
    [[noreturn]] void failEnded() const {
        fail(m_input, "the header says " + (m_counted ? *m_counted : std::string("more")) +
                          " but the file ends after " + std::to_string(m_index));
    }

    template <typename T> static T load(const std::uint8_t *raw) {
        T value;
        std::memcpy(&value, raw, sizeof value);
        return value;
    }

    const ReadInput &m_input;
    Encoding m_encoding;
    std::size_t m_pos;
    TextCursor m_text;
    const std::string *m_counted = nullptr;
    const std::string *m_name = nullptr;
    std::uint64_t m_index = 0;
};

int indexOf(const Element &e, std::initializer_list<std::string_view> names) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
        for (std::string_view n : names)
            if (e.properties[i].name == n && !e.properties[i].listCount) return int(i);
    return -1;
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

} // namespace

MeshFileData readPly(const ReadInput &input) {
    const Header header = readHeader(input);
    BodyReader body(input, header);
    MeshFileData data;
    MeshPart &part = data.parts.emplace_back();
    bool sawVertices = false, sawFaces = false;
    std::size_t skippedFaces = 0;
    std::vector<double> values;
    std::vector<std::uint32_t> polygon;
    for (const Element &e : header.elements) {
        const std::string counted =
            std::to_string(e.count) + " " + (e.count == 1 ? e.name : e.name == "vertex" ? "vertices" : e.name + "s");
        if (!body.canHold(e.count, e.properties.size(), e.minimumBytes()))
            fail(input, "the header says " + counted + ", more than the " + std::to_string(body.bytesLeft()) +
                            " bytes after it can hold");
        if (e.properties.empty()) continue; // holds nothing, however many it counts
        const bool isVertex = e.name == "vertex" && !sawVertices;
        const bool isFace = e.name == "face" && !sawFaces;
        const int x = indexOf(e, {"x"}), y = indexOf(e, {"y"}), z = indexOf(e, {"z"});
        const int nx = indexOf(e, {"nx"}), ny = indexOf(e, {"ny"}), nz = indexOf(e, {"nz"});
        const int r = indexOf(e, {"red", "r", "diffuse_red"}), g = indexOf(e, {"green", "g", "diffuse_green"}),
                  b = indexOf(e, {"blue", "b", "diffuse_blue"});
        int corners = -1;
        for (std::size_t i = 0; i < e.properties.size(); ++i)
            if (e.properties[i].listCount && (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
                corners = int(i);
        if (isVertex) {
            if (x < 0 || y < 0 || z < 0) fail(input, "the vertex element has no x, y and z properties");
            if (e.count > std::numeric_limits<std::uint32_t>::max()) fail(input, "more vertices than mvcl supports");
            part.positions.reserve(e.count);
            if (nx >= 0 && ny >= 0 && nz >= 0) part.normals.reserve(e.count);
            if (r >= 0 && g >= 0 && b >= 0) part.colors.reserve(e.count);
        }
        if (isFace && corners < 0) fail(input, "the face element has no vertex_indices list");
        if (isFace) part.triangles.reserve(std::min<std::uint64_t>(e.count, input.limits.maxTriangles));
        for (std::uint64_t i = 0; i < e.count; ++i) {
            body.beginElement(counted, e.name, i);
            values.clear();
            polygon.clear();
            for (std::size_t p = 0; p < e.properties.size(); ++p) {
                const Property &prop = e.properties[p];
                if (!prop.listCount) {
                    values.push_back(body.scalar(prop.type));
                    continue;
                }
                values.push_back(0.0);
                const double n = body.scalar(*prop.listCount);
                if (!(n >= 0.0) || n > double(kMaxPolygonCorners))
                    fail(input, e.name + " " + std::to_string(i) + ": a list of " + std::to_string(n) + " values");
                const bool keep = isFace && int(p) == corners;
                for (std::uint64_t k = 0; k < std::uint64_t(n); ++k) {
                    const double v = body.scalar(prop.type);
                    if (!keep) continue;
                    if (!(v >= 0.0) || v >= double(std::numeric_limits<std::uint32_t>::max()))
                        fail(input, "face " + std::to_string(i) + ": vertex index " + std::to_string(v) + " is out of range");
                    polygon.push_back(std::uint32_t(v));
                }
            }
            body.endElement();
            if (isVertex) {
                const glm::dvec3 pos(values[std::size_t(x)], values[std::size_t(y)], values[std::size_t(z)]);
                if (!isFinite(pos))
                    fail(input, "vertex " + std::to_string(i) + " is (" + std::to_string(pos.x) + ", " +
                                    std::to_string(pos.y) + ", " + std::to_string(pos.z) + "), not finite");
                part.positions.push_back(pos);
                if (part.normals.capacity())
                    part.normals.emplace_back(values[std::size_t(nx)], values[std::size_t(ny)], values[std::size_t(nz)]);
                if (part.colors.capacity()) {
                    // 8-bit colours are display (sRGB) values; float ones are taken as 0..1 sRGB too.
                    const double scale = e.properties[std::size_t(r)].type == ScalarType::Float32 ||
                                                 e.properties[std::size_t(r)].type == ScalarType::Float64
                                             ? 1.0
                                             : 1.0 / 255.0;
                    glm::vec3 c;
                    for (int k = 0; k < 3; ++k) {
                        const double v = values[std::size_t(k == 0 ? r : k == 1 ? g : b)] * scale;
                        c[k] = float(srgbToLinear(std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.0));
                    }
                    part.colors.push_back(c);
                }
            } else if (isFace) {
                if (polygon.size() < 3) {
                    ++skippedFaces;
                    continue;
                }
                for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
                    checkTriangleCount(input, part.triangles.size() + 1);
                    part.triangles.emplace_back(polygon[0], polygon[k], polygon[k + 1]);
                }
            }
        }
        sawVertices = sawVertices || isVertex;
        sawFaces = sawFaces || isFace;
        if (!isVertex && !isFace && e.count > 0)
            data.warnings.push_back("the " + e.name + " element is not read");
    }
    if (!sawVertices) fail(input, "the PLY file has no vertex element");
    if (!sawFaces || part.triangles.empty()) fail(input, "the PLY file has no faces (a point cloud is not a surface)");
    for (std::size_t t = 0; t < part.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
            if (part.triangles[t][k] >= part.positions.size())
                fail(input, "a face refers to vertex " + std::to_string(part.triangles[t][k]) + ", but there are only " +
                                std::to_string(part.positions.size()) + " vertices");
    if (skippedFaces) data.warnings.push_back(std::to_string(skippedFaces) + " faces with fewer than 3 corners skipped");
    if (!body.atEnd()) data.warnings.push_back(std::to_string(body.bytesLeft()) + " bytes after the last element ignored");
    return data;
}

} // namespace mvcl::meshfile
