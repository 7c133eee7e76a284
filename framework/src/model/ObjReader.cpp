// Wavefront OBJ through tinyobjloader, which parses; everything it hands back is checked here:
// tinyobjloader keeps indices it cannot resolve, and reads a number it cannot parse ("nan",
// "1e999", "x") as 0, so the numbers of v, vn and vt lines are checked before it runs. Files
// without vertex colours are parsed through its callback interface, straight into mvcl's
// arrays. Each group or object ("g", "o") becomes one part per material, named after it; MTL
// colours become materials. Polygons are split into fans here, not by tinyobjloader, so that
// nothing reads a vertex before its index is checked.

#include "MeshFileData_p.h"

#include <tiny_obj_loader.h>

#include <glm/common.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <istream>
#include <map>
#include <sstream>
#include <streambuf>
#include <unordered_map>

namespace mvcl::meshfile {

namespace {

/// An istream over the file's bytes, without a copy.
class MemoryBuffer : public std::streambuf {
public:
    explicit MemoryBuffer(std::span<const std::uint8_t> bytes) {
        char *begin = const_cast<char *>(reinterpret_cast<const char *>(bytes.data())); // read only
        setg(begin, begin, begin + bytes.size());
    }
};

/// Material libraries are read only from the OBJ's folder or below it: a hostile file must not
/// make the loader open /etc/passwd or a device.
class FolderMaterialReader : public tinyobj::MaterialReader {
public:
    FolderMaterialReader(const std::filesystem::path &directory, std::vector<std::string> &warnings)
        : m_directory(directory), m_warnings(warnings) {}

    bool operator()(const std::string &library, std::vector<tinyobj::material_t> *materials,
                    std::map<std::string, int> *names, std::string *warn, std::string *err) override {
        const std::filesystem::path relative(library);
        const bool inside = !relative.empty() && relative.is_relative() &&
                            std::none_of(relative.begin(), relative.end(), [](const auto &c) { return c == ".."; });
        if (m_directory.empty() || !inside) {
            m_warnings.push_back("material library '" + library + "' not read" +
                                 (m_directory.empty() ? "" : " (only files beside the OBJ file are read)"));
            return false;
        }
        const std::filesystem::path path = m_directory / relative;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec)) {
            m_warnings.push_back("material library '" + library + "' not found; default materials used");
            return false;
        }
        std::ifstream stream(path, std::ios::binary);
        tinyobj::LoadMtl(names, materials, &stream, warn, err);
        if (materials->empty()) { // and LoadObjWithCallback would index its first material
            m_warnings.push_back("material library '" + library + "' holds no materials; default materials used");
            return false;
        }
        return true;
    }

private:
    std::filesystem::path m_directory;
    std::vector<std::string> &m_warnings;
};

/// Whether `word` is a decimal number that is certainly finite as a double: [+-]digits[.digits]
/// with an exponent of at most two digits and at most 200 digits in all. Anything else (other
/// spellings, huge exponents, "nan", "inf") goes to std::from_chars for the exact verdict; this is
/// only the fast path of the check that runs over every v, vn and vt line.
bool isPlainFiniteNumber(std::string_view word) {
    std::size_t i = 0, digits = 0;
    const std::size_t n = word.size();
    if (i < n && (word[i] == '+' || word[i] == '-')) ++i;
    while (i < n && word[i] >= '0' && word[i] <= '9') ++i, ++digits;
    if (i < n && word[i] == '.') {
        ++i;
        while (i < n && word[i] >= '0' && word[i] <= '9') ++i, ++digits;
    }
    if (digits == 0 || digits > 200) return false;
    if (i == n) return true;
    if (word[i] != 'e' && word[i] != 'E') return false;
    ++i;
    if (i < n && (word[i] == '+' || word[i] == '-')) ++i;
    const std::size_t exponentStart = i;
    while (i < n && word[i] >= '0' && word[i] <= '9') ++i;
    return i == n && i > exponentStart && i - exponentStart <= 2;
}

/// What the pass over the text found besides bad numbers.
struct ObjTextSummary {
    std::size_t vertices = 0, normals = 0; ///< `v` and `vn` lines, to reserve for them
    std::size_t linesAndPoints = 0; ///< `l` and `p` lines, which are not ray traced
    bool vertexColours = false;     ///< a `v` line with more than three numbers (colours, or w)
};

/// Every number on the v, vn and vt lines parses and is finite; fails naming the line otherwise.
/// One pass over the bytes, a plain syntax check per number (std::from_chars only for what
/// that does not settle): it runs before tinyobjloader over the whole file, so it must cost
/// little beside tinyobjloader's own parse. It counts what the parse will hand over, too.
ObjTextSummary scanObjText(const ReadInput &input) {
    ObjTextSummary summary;
    const char *const begin = reinterpret_cast<const char *>(input.bytes.data());
    const char *const end = begin + input.bytes.size();
    const auto isBlank = [](char c) { return c == ' ' || c == '\t'; };
    std::size_t line = 0;
    for (const char *p = begin; p < end;) {
        ++line;
        const char *eol = static_cast<const char *>(std::memchr(p, '\n', std::size_t(end - p)));
        if (!eol) eol = end;
        const char *c = p;
        p = eol + 1;
        while (c < eol && isBlank(*c)) ++c;
        if (eol - c < 2) continue;
        if ((c[0] == 'l' || c[0] == 'p') && isBlank(c[1])) ++summary.linesAndPoints;
        if (c[0] != 'v') continue;
        std::string_view keyword;
        if (isBlank(c[1])) keyword = "v";
        else if ((c[1] == 'n' || c[1] == 't') && eol - c > 2 && isBlank(c[2])) keyword = c[1] == 'n' ? "vn" : "vt";
        else continue;
        c += keyword.size();
        if (keyword == "v") ++summary.vertices;
        if (keyword == "vn") ++summary.normals;
        int numbers = 0;
        for (;;) {
            while (c < eol && (isBlank(*c) || *c == '\r')) ++c;
            if (c == eol || *c == '#') break;
            const char *wordEnd = c;
            while (wordEnd < eol && !isBlank(*wordEnd) && *wordEnd != '\r') ++wordEnd;
            const std::string_view word(c, std::size_t(wordEnd - c));
            c = wordEnd;
            if (keyword == "v" && ++numbers > 3) summary.vertexColours = true;
            if (isPlainFiniteNumber(word)) continue;
            const std::string_view digits = word.starts_with('+') ? word.substr(1) : word;
            double value = 0.0;
            const auto [stop, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
            if (ec == std::errc::result_out_of_range || (ec == std::errc() && stop == digits.data() + digits.size() && !std::isfinite(value)))
                fail(input, "line " + std::to_string(line) + ": " + std::string(keyword) + " coordinate '" +
                                std::string(word.substr(0, 40)) + "' is not finite");
            if (ec != std::errc() || stop != digits.data() + digits.size())
                fail(input, "line " + std::to_string(line) + ": " + std::string(keyword) + " coordinate '" +
                                std::string(word.substr(0, 40)) + "' is not a number");
        }
    }
    return summary;
}

glm::vec3 colour(const tinyobj::real_t (&c)[3]) {
    glm::vec3 v{float(c[0]), float(c[1]), float(c[2])};
    for (int k = 0; k < 3; ++k) v[k] = std::isfinite(v[k]) ? std::clamp(v[k], 0.f, 1.f) : 0.f;
    return v;
}

Material materialOf(const tinyobj::material_t &m) {
    Material out;
    out.name = m.name;
    out.diffuse = colour(m.diffuse);
    // MTL files set Ka anywhere from black to white regardless of Kd; the diffuse colour under
    // the scene's ambient light reads as the other loaders' materials do.
    out.ambient = out.diffuse;
    const glm::vec3 ks = colour(m.specular);
    out.specular = std::max({ks.x, ks.y, ks.z});
    if (out.specular > 0.f) out.specularColor = ks / out.specular;
    out.shininess = std::isfinite(m.shininess) ? std::clamp(float(m.shininess), 1.f, 1000.f) : 32.f;
    out.emission = colour(m.emission);
    const float dissolve = std::isfinite(m.dissolve) ? std::clamp(float(m.dissolve), 0.f, 1.f) : 1.f;
    out.transparency = 1.f - dissolve;
    if (std::isfinite(m.ior) && m.ior >= 1.0) out.ior = float(m.ior);
    return out;
}

/// One part per (shape, material) with its own vertex numbering: OBJ indexes positions and
/// normals separately, a part's vertex is a (position, normal) pair. Without normals a part's
/// vertex is a position, found through one array over the file's positions (which part last
/// numbered it, and as what) instead of a hash map: a position shared by parts used in turns is
/// then copied into each, which changes no geometry.
class PartBuilder {
public:
    PartBuilder(const ReadInput &input, const tinyobj::attrib_t &attrib, bool hasColors)
        : m_input(input), m_attrib(attrib), m_hasColors(hasColors), m_owner(attrib.vertices.size() / 3, kNone),
          m_number(attrib.vertices.size() / 3, 0) {}

    std::uint32_t vertex(MeshPart &part, std::size_t partId, std::unordered_map<std::uint64_t, std::uint32_t> &numbers,
                         const tinyobj::index_t &corner, bool withNormals) {
        const std::size_t positions = m_attrib.vertices.size() / 3;
        const std::size_t normals = m_attrib.normals.size() / 3;
        const auto where = [&part] { return part.name.empty() ? std::string() : "'" + part.name + "': "; };
        if (corner.vertex_index < 0 || std::size_t(corner.vertex_index) >= positions)
            fail(m_input, where() + "a face refers to vertex " + std::to_string(corner.vertex_index + 1) +
                              ", but the file has " + std::to_string(positions) + " vertices");
        const int normal = withNormals ? corner.normal_index : -1;
        if (normal >= 0 && std::size_t(normal) >= normals)
            fail(m_input, where() + "a face refers to normal " + std::to_string(normal + 1) +
                              ", but the file has " + std::to_string(normals) + " normals");
        const std::size_t v = std::size_t(corner.vertex_index);
        const auto number = std::uint32_t(part.positions.size());
        if (withNormals) {
            const std::uint64_t key = (std::uint64_t(std::uint32_t(corner.vertex_index)) << 32) | std::uint32_t(normal);
            const auto [it, inserted] = numbers.try_emplace(key, number);
            if (!inserted) return it->second;
        } else {
            if (m_owner[v] == partId) return m_number[v];
            m_owner[v] = partId;
            m_number[v] = number;
        }
        const glm::dvec3 p(m_attrib.vertices[3 * v], m_attrib.vertices[3 * v + 1], m_attrib.vertices[3 * v + 2]);
        if (!isFinite(p))
            fail(m_input, "vertex " + std::to_string(v + 1) + " is (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                              ", " + std::to_string(p.z) + "), not finite");
        part.positions.push_back(p);
        if (withNormals) {
            const std::size_t n = std::size_t(normal);
            part.normals.emplace_back(m_attrib.normals[3 * n], m_attrib.normals[3 * n + 1], m_attrib.normals[3 * n + 2]);
        }
        if (m_hasColors) {
            glm::vec3 c{float(m_attrib.colors[3 * v]), float(m_attrib.colors[3 * v + 1]), float(m_attrib.colors[3 * v + 2])};
            for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) ? std::clamp(c[k], 0.f, 1.f) : 0.f;
            part.colors.push_back(c);
        }
        return number;
    }

private:
    static constexpr std::size_t kNone = ~std::size_t(0);
    const ReadInput &m_input;
    const tinyobj::attrib_t &m_attrib;
    bool m_hasColors;
    std::vector<std::size_t> m_owner;   ///< per file position: the part that numbered it last
    std::vector<std::uint32_t> m_number; ///< and the number it has there
};

/// One group or object of the file as parsed: its faces' corners, corner counts and materials.
struct ObjGroup {
    std::string name;
    std::vector<tinyobj::index_t> corners; ///< 0-based; normal_index -1 when a corner names none
    std::vector<std::uint32_t> cornerCounts;
    std::vector<int> materials; ///< per face; -1 = none or not in the library
};

struct ObjParse {
    tinyobj::attrib_t attrib;
    std::vector<ObjGroup> groups;
    std::vector<tinyobj::material_t> materials;
};

/// tinyobjloader's messages: the first 8 lines are warnings.
void keepWarnings(const std::string &warn, MeshFileData &data) {
    std::istringstream lines(warn);
    std::size_t count = 0;
    for (std::string line; std::getline(lines, line);)
        if (!line.empty() && count++ < 8) data.warnings.push_back(line);
}

/// Through tinyobj::LoadObj, which reads vertex colours (the callback interface does not).
ObjParse parseWithLoadObj(const ReadInput &input, MeshFileData &data) {
    MemoryBuffer buffer(input.bytes);
    std::istream stream(&buffer);
    FolderMaterialReader materialReader(input.directory, data.warnings);
    ObjParse parse;
    std::vector<tinyobj::shape_t> shapes;
    std::string warn, err;
    const bool ok = tinyobj::LoadObj(&parse.attrib, &shapes, &parse.materials, &warn, &err, &stream, &materialReader,
                                     /*triangulate=*/false, /*default_vcols_fallback=*/false);
    if (!ok) {
        std::string problem = err.empty() ? "not a valid OBJ file" : err;
        fail(input, problem.substr(0, problem.find('\n')));
    }
    keepWarnings(warn, data);
    for (tinyobj::shape_t &shape : shapes) {
        ObjGroup &group = parse.groups.emplace_back();
        group.name = std::move(shape.name);
        group.corners = std::move(shape.mesh.indices);
        group.cornerCounts.assign(shape.mesh.num_face_vertices.begin(), shape.mesh.num_face_vertices.end());
        group.materials = std::move(shape.mesh.material_ids);
    }
    return parse;
}

/// Through tinyobj::LoadObjWithCallback, straight into ObjParse: the same parser of lines and
/// numbers without LoadObj's own face and shape arrays, which take about half its time. The
/// callbacks do what LoadObj does with them: `g` and `o` start a group (named after all of a
/// `g` line's names, joined by spaces), `usemtl` sets the faces' material, indices are made
/// 0-based (negative ones count back from the last vertex).
ObjParse parseWithCallbacks(const ReadInput &input, const ObjTextSummary &summary, MeshFileData &data) {
    struct State {
        const ReadInput &input;
        ObjParse parse;
        int material = -1;
        std::vector<std::string> &warnings;
        ObjGroup &group() { return parse.groups.back(); }
        void startGroup(std::string name) {
            if (!group().cornerCounts.empty()) parse.groups.emplace_back();
            group().name = std::move(name);
        }
    } state{input, {}, -1, data.warnings};
    state.parse.attrib.vertices.reserve(3 * summary.vertices);
    state.parse.attrib.normals.reserve(3 * summary.normals);
    state.parse.groups.emplace_back();

    tinyobj::callback_t callbacks;
    callbacks.vertex_cb = [](void *user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z, tinyobj::real_t) {
        std::vector<tinyobj::real_t> &v = static_cast<State *>(user)->parse.attrib.vertices;
        v.insert(v.end(), {x, y, z});
    };
    callbacks.normal_cb = [](void *user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) {
        std::vector<tinyobj::real_t> &n = static_cast<State *>(user)->parse.attrib.normals;
        n.insert(n.end(), {x, y, z});
    };
    callbacks.index_cb = [](void *user, tinyobj::index_t *indices, int count) {
        State &st = *static_cast<State *>(user);
        ObjGroup &group = st.group();
        const auto vertices = int(st.parse.attrib.vertices.size() / 3);
        const auto normals = int(st.parse.attrib.normals.size() / 3);
        for (int i = 0; i < count; ++i) {
            tinyobj::index_t corner = indices[i];
            if (corner.vertex_index == 0) fail(st.input, "a face has vertex index 0 (OBJ counts from 1)");
            corner.vertex_index = corner.vertex_index > 0 ? corner.vertex_index - 1 : vertices + corner.vertex_index;
            corner.normal_index = corner.normal_index > 0   ? corner.normal_index - 1
                                  : corner.normal_index < 0 ? normals + corner.normal_index
                                                            : -1;
            corner.texcoord_index = -1; // texture coordinates are not read
            group.corners.push_back(corner);
        }
        group.cornerCounts.push_back(std::uint32_t(count));
        group.materials.push_back(st.material);
    };
    callbacks.usemtl_cb = [](void *user, const char *name, int material) {
        State &st = *static_cast<State *>(user);
        st.material = material;
        if (material < 0 && st.warnings.size() < 8)
            st.warnings.push_back("material [ '" + std::string(name) + "' ] not found in .mtl");
    };
    callbacks.mtllib_cb = [](void *user, const tinyobj::material_t *materials, int count) {
        static_cast<State *>(user)->parse.materials.assign(materials, materials + count);
    };
    callbacks.group_cb = [](void *user, const char **names, int count) {
        std::string name;
        for (int i = 0; i < count; ++i) {
            if (i > 0) name += ' ';
            name += names[i];
        }
        static_cast<State *>(user)->startGroup(std::move(name));
    };
    callbacks.object_cb = [](void *user, const char *name) { static_cast<State *>(user)->startGroup(name); };

    MemoryBuffer buffer(input.bytes);
    std::istream stream(&buffer);
    FolderMaterialReader materialReader(input.directory, data.warnings);
    std::string warn, err;
    if (!tinyobj::LoadObjWithCallback(stream, callbacks, &state, &materialReader, &warn, &err)) {
        std::string problem = err.empty() ? "not a valid OBJ file" : err;
        fail(input, problem.substr(0, problem.find('\n')));
    }
    keepWarnings(warn, data);
    if (state.group().cornerCounts.empty()) state.parse.groups.pop_back();
    return std::move(state.parse);
}

} // namespace

MeshFileData readObj(const ReadInput &input) {
    const ObjTextSummary summary = scanObjText(input);
    MeshFileData data;
    ObjParse parse = summary.vertexColours ? parseWithLoadObj(input, data) : parseWithCallbacks(input, summary, data);
    const tinyobj::attrib_t &attrib = parse.attrib;
    const std::vector<tinyobj::material_t> &materials = parse.materials;
    for (const tinyobj::material_t &m : materials) data.materials.push_back(materialOf(m));

    const bool hasColors = !attrib.colors.empty() && attrib.colors.size() == attrib.vertices.size();
    PartBuilder builder(input, attrib, hasColors);
    std::size_t triangles = 0, skippedFaces = 0;
    for (const ObjGroup &shape : parse.groups) {
        // A part has per-vertex normals only when every corner of it names one.
        const bool withNormals = !shape.corners.empty() && !attrib.normals.empty() &&
                                 std::all_of(shape.corners.begin(), shape.corners.end(),
                                             [](const tinyobj::index_t &i) { return i.normal_index >= 0; });
        std::map<int, std::size_t> partOfMaterial;
        std::vector<std::unordered_map<std::uint64_t, std::uint32_t>> numbers;
        const std::size_t firstPart = data.parts.size();
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.cornerCounts.size(); ++f) {
            const std::size_t n = shape.cornerCounts[f];
            if (offset + n > shape.corners.size()) fail(input, "'" + shape.name + "': face " + std::to_string(f) + " is cut short");
            const int materialId = f < shape.materials.size() ? shape.materials[f] : -1;
            const int material = materialId >= 0 && std::size_t(materialId) < materials.size() ? materialId : -1;
            if (n < 3) {
                ++skippedFaces;
                offset += n;
                continue;
            }
            const auto [it, inserted] = partOfMaterial.try_emplace(material, data.parts.size());
            if (inserted) {
                MeshPart &part = data.parts.emplace_back();
                part.name = shape.name;
                part.material = material;
                part.group = int(&shape - parse.groups.data());
                numbers.emplace_back();
            }
            MeshPart &part = data.parts[it->second];
            auto &partNumbers = numbers[it->second - firstPart];
            const std::uint32_t first = builder.vertex(part, it->second, partNumbers, shape.corners[offset], withNormals);
            std::uint32_t previous = builder.vertex(part, it->second, partNumbers, shape.corners[offset + 1], withNormals);
            for (std::size_t k = 2; k < n; ++k) {
                const std::uint32_t next = builder.vertex(part, it->second, partNumbers, shape.corners[offset + k], withNormals);
                checkTriangleCount(input, ++triangles);
                part.triangles.emplace_back(first, previous, next);
                previous = next;
            }
            offset += n;
        }
    }
    if (skippedFaces) data.warnings.push_back(std::to_string(skippedFaces) + " faces with fewer than 3 corners skipped");
    if (summary.linesAndPoints) data.warnings.push_back("lines and points are skipped (only triangles are ray traced)");
    if (triangles == 0) fail(input, "the OBJ file holds no faces");
    return data;
}

} // namespace mvcl::meshfile
