#include "MeshFileMemoryEstimate_p.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <string_view>

namespace mvcl::meshfile {

namespace {

detail::GeometryMemoryEstimate estimate(double triangles, double vertices, double fileBytes) {
    detail::GeometryMemoryEstimate e;
    e.triangles = triangles;
    e.vertices = vertices;
    e.bytes = triangles * (detail::kEstimatedBytesPerTriangle + kReaderBytesPerTriangle) +
              vertices * (detail::kEstimatedBytesPerVertex + kReaderBytesPerVertex) + fileBytes;
    return e;
}

std::string_view textOf(std::span<const std::uint8_t> bytes) {
    return {reinterpret_cast<const char *>(bytes.data()), bytes.size()};
}

/// `element NAME COUNT` lines of a PLY header within `text`; nothing when the header does not end there.
std::optional<detail::GeometryMemoryEstimate> plyHeaderEstimate(std::string_view text, std::uint64_t fileSize) {
    const std::size_t end = text.find("end_header");
    if (!text.starts_with("ply") || end == std::string_view::npos) return std::nullopt;
    double vertices = 0.0, faces = 0.0;
    for (std::size_t pos = 0; pos < end;) {
        std::size_t eol = text.find('\n', pos);
        if (eol == std::string_view::npos || eol > end) eol = end;
        std::string_view line = text.substr(pos, eol - pos);
        pos = eol + 1;
        if (!line.starts_with("element ")) continue;
        line.remove_prefix(8);
        const std::size_t space = line.find(' ');
        if (space == std::string_view::npos) continue;
        const std::string_view name = line.substr(0, space);
        std::string_view digits = line.substr(space + 1);
        while (!digits.empty() && (digits.back() == '\r' || digits.back() == ' ')) digits.remove_suffix(1);
        std::uint64_t count = 0;
        if (std::from_chars(digits.data(), digits.data() + digits.size(), count).ec != std::errc()) continue;
        // The reader reads the first of each; a malformed header is its to report.
        if (name == "vertex" && vertices == 0.0) vertices = double(count);
        else if (name == "face" && faces == 0.0) faces = double(count);
    }
    return estimate(faces, vertices, double(fileSize));
}

} // namespace

std::optional<detail::GeometryMemoryEstimate> estimateFromHeader(std::span<const std::uint8_t> head,
                                                                 std::uint64_t fileSize, MeshFormat format) {
    if (format == MeshFormat::Ply) return plyHeaderEstimate(textOf(head), fileSize);
    if (format != MeshFormat::Stl || head.size() < 84) return std::nullopt;
    std::uint32_t count = 0;
    std::memcpy(&count, head.data() + 80, sizeof count);
    if (84 + std::uint64_t(count) * 50 != fileSize) return std::nullopt; // ASCII (or broken: the reader says)
    // Welded corners: a closed mesh has about half as many vertices as triangles.
    return estimate(double(count), double(count) / 2.0, double(fileSize));
}

detail::GeometryMemoryEstimate estimateFromText(std::span<const std::uint8_t> bytes, MeshFormat format,
                                                std::uint64_t budgetBytes) {
    const double size = double(bytes.size());
    // OBJ: "f 1 2 3\n" is 8 bytes and each further corner (a triangle more) at least 2;
    // "v 0 0 0\n" is 8 bytes. ASCII STL: a facet is far more than 64 bytes.
    const detail::GeometryMemoryEstimate bound =
        format == MeshFormat::Obj ? estimate(size / 2.0, size / 8.0, size) : estimate(size / 64.0, size / 64.0 * 3.0, size);
    if (bound.bytes <= double(budgetBytes)) return bound;

    const std::string_view text = textOf(bytes);
    double triangles = 0.0, vertices = 0.0;
    for (std::size_t pos = 0; pos < text.size();) {
        std::size_t eol = text.find('\n', pos);
        if (eol == std::string_view::npos) eol = text.size();
        std::string_view line = text.substr(pos, eol - pos);
        pos = eol + 1;
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string_view::npos) continue;
        line.remove_prefix(first);
        if (format == MeshFormat::Obj) {
            if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t')) continue;
            if (line[0] == 'v') {
                vertices += 1.0;
            } else if (line[0] == 'f') {
                int corners = 0;
                for (std::size_t i = 1; i < line.size(); ++i)
                    if ((line[i - 1] == ' ' || line[i - 1] == '\t') && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++corners;
                triangles += double(std::max(corners - 2, 0));
            }
        } else if (line.starts_with("vertex")) {
            vertices += 1.0; // before welding: an upper bound
        }
    }
    if (format == MeshFormat::Stl) triangles = vertices / 3.0;
    return estimate(triangles, format == MeshFormat::Stl ? triangles / 2.0 : vertices, size);
}

} // namespace mvcl::meshfile
