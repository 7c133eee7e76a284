#include "GltfImageDecoder_p.h"

#include <stb_image.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <new>
#include <vector>

namespace mvcl::gltf {

namespace {

bool startsWith(std::span<const std::uint8_t> bytes, const char *magic, std::size_t offset = 0) {
    const std::size_t n = std::strlen(magic);
    return bytes.size() >= offset + n && std::memcmp(bytes.data() + offset, magic, n) == 0;
}

} // namespace

std::string GltfImageDecoder::formatOf(std::span<const std::uint8_t> bytes) {
    if (startsWith(bytes, "\x89PNG\r\n\x1a\n")) return "PNG";
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "JPEG";
    if (startsWith(bytes, "\xABKTX 20\xBB")) return "KTX2";
    if (startsWith(bytes, "\xABKTX 11\xBB")) return "KTX";
    if (startsWith(bytes, "RIFF") && startsWith(bytes, "WEBP", 8)) return "WebP";
    if (startsWith(bytes, "sB")) return "Basis";
    if (startsWith(bytes, "DDS ")) return "DDS";
    return "";
}

std::shared_ptr<const TextureImage> GltfImageDecoder::decode(std::span<const std::uint8_t> bytes,
                                                             const std::string &name, TextureColorSpace space,
                                                             std::string &problem) {
    const std::string format = formatOf(bytes);
    if (format.empty()) {
        problem = "is not a PNG or JPEG image";
        return nullptr;
    }
    if (format != "PNG" && format != "JPEG") {
        problem = "is a " + format + " image, which mvcl does not decode";
        return nullptr;
    }
    // stb_image reads from memory only: nothing is opened on disk. The header first, so that the
    // limits hold before a pixel is decoded.
    if (bytes.size() > std::size_t(INT_MAX)) {
        problem = "is too large to decode (" + std::to_string(bytes.size()) + " bytes)";
        return nullptr;
    }
    const auto *data = reinterpret_cast<const stbi_uc *>(bytes.data());
    const int length = int(bytes.size());
    int headerWidth = 0, headerHeight = 0, channels = 0;
    if (!stbi_info_from_memory(data, length, &headerWidth, &headerHeight, &channels)) {
        problem = "cannot be decoded as " + format + ": " + stbi_failure_reason();
        return nullptr;
    }
    const std::uint64_t width = std::uint64_t(std::max(headerWidth, 0));
    const std::uint64_t height = std::uint64_t(std::max(headerHeight, 0));
    if (width == 0 || height == 0 || channels < 1) {
        problem = "has no pixels";
        return nullptr;
    }
    if (width * height > m_maxPixels) {
        problem = "is " + std::to_string(width) + "×" + std::to_string(height) + " pixels, more than the limit of " +
                  std::to_string(m_maxPixels);
        return nullptr;
    }
    // RGBA8 and a mip chain of a third more.
    const std::uint64_t bytesNeeded = width * height * 4 * 4 / 3;
    if (m_bytesUsed + bytesNeeded > m_maxTotalBytes) {
        problem = "would take the textures past their memory limit of " + std::to_string(m_maxTotalBytes) + " bytes";
        return nullptr;
    }
    // Grey, grey + alpha, RGB and RGBA all become RGBA (alpha straight, as glTF has it; 16-bit
    // PNG channels keep their high 8 bits).
    int decodedWidth = 0, decodedHeight = 0;
    std::unique_ptr<stbi_uc, void (*)(void *)> pixels(
        stbi_load_from_memory(data, length, &decodedWidth, &decodedHeight, &channels, 4), &stbi_image_free);
    if (!pixels) {
        const std::string reason = stbi_failure_reason();
        problem = reason == "outofmem" ? "does not fit in memory" : "cannot be decoded as " + format + ": " + reason;
        return nullptr;
    }
    if (std::uint64_t(decodedWidth) != width || std::uint64_t(decodedHeight) != height) {
        problem = "cannot be decoded as " + format + ": its size changed between header and pixels";
        return nullptr;
    }
    std::vector<std::uint8_t> rgba;
    try {
        rgba.assign(pixels.get(), pixels.get() + std::size_t(width * height) * 4);
    } catch (const std::bad_alloc &) {
        problem = "does not fit in memory";
        return nullptr;
    }
    auto image = std::make_shared<const TextureImage>(name, int(width), int(height), std::move(rgba), space);
    m_bytesUsed += image->memoryBytes();
    return image;
}

} // namespace mvcl::gltf
