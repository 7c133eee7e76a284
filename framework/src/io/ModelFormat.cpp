#include "ModelFormat_p.h"

#include <algorithm>
#include <cstring>

namespace mvcl::detail {

namespace {

bool startsWith(std::span<const std::uint8_t> head, std::string_view prefix) {
    return head.size() >= prefix.size() && std::memcmp(head.data(), prefix.data(), prefix.size()) == 0;
}

bool isText(std::span<const std::uint8_t> head) {
    return std::all_of(head.begin(), head.end(), [](std::uint8_t c) { return c >= 0x20 || c == '\n' || c == '\r' || c == '\t'; });
}

/// The first word of the first line that is neither blank nor a comment.
std::string_view firstKeyword(std::span<const std::uint8_t> head) {
    const std::string_view text(reinterpret_cast<const char *>(head.data()), head.size());
    std::size_t pos = 0;
    while (pos < text.size()) {
        pos = text.find_first_not_of(" \t\r\n", pos);
        if (pos == std::string_view::npos) return {};
        if (text[pos] != '#') {
            const std::size_t end = text.find_first_of(" \t\r\n", pos);
            return text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
        }
        pos = text.find('\n', pos);
    }
    return {};
}

} // namespace

std::optional<ModelFormat> modelFormatFromExtension(std::string_view extension) {
    std::string ext(extension);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".gltf" || ext == ".glb") return ModelFormat::Gltf;
    if (ext == ".obj") return ModelFormat::Obj;
    if (ext == ".stl") return ModelFormat::Stl;
    if (ext == ".ply") return ModelFormat::Ply;
    return std::nullopt;
}

std::optional<ModelFormat> modelFormatFromContent(std::span<const std::uint8_t> head, std::uint64_t size) {
    if (startsWith(head, "glTF")) return ModelFormat::Gltf;
    if (startsWith(head, "ply\n") || startsWith(head, "ply\r\n")) return ModelFormat::Ply;
    if (size >= 84 && head.size() >= 84) {
        std::uint32_t count;
        std::memcpy(&count, head.data() + 80, sizeof count);
        if (84 + std::uint64_t(count) * 50 == size) return ModelFormat::Stl;
    }
    if (!isText(head)) return std::nullopt;
    const std::string_view keyword = firstKeyword(head);
    if (keyword.starts_with("{")) return ModelFormat::Gltf;
    if (keyword == "solid") return ModelFormat::Stl;
    static constexpr std::string_view kObjKeywords[] = {"v", "vn", "vt", "f", "o", "g", "s", "mtllib", "usemtl"};
    if (std::find(std::begin(kObjKeywords), std::end(kObjKeywords), keyword) != std::end(kObjKeywords))
        return ModelFormat::Obj;
    return std::nullopt;
}

std::string otherFileKind(std::span<const std::uint8_t> head) {
    if (startsWith(head, "\x89PNG")) return "a PNG image";
    if (startsWith(head, "\xff\xd8\xff")) return "a JPEG image";
    if (startsWith(head, "%PDF")) return "a PDF document";
    if (startsWith(head, "PK\x03\x04")) return "a ZIP archive";
    if (startsWith(head, "\x1f\x8b")) return "gzip-compressed data";
    if (startsWith(head, "\x7f" "ELF")) return "a program";
    if (startsWith(head, "OFF")) return "an OFF mesh (not read; convert it to PLY or OBJ)";
    return {};
}

const char *modelFormatName(ModelFormat format) {
    switch (format) {
    case ModelFormat::Gltf: return "glTF";
    case ModelFormat::Obj: return "OBJ";
    case ModelFormat::Stl: return "STL";
    case ModelFormat::Ply: return "PLY";
    }
    return "?";
}

} // namespace mvcl::detail
