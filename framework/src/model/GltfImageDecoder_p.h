#pragma once
/// \file GltfImageDecoder_p.h
/// Private to the glTF loader: decodes a glTF image's encoded bytes (PNG, JPEG) with stb_image
/// from memory, refusing images larger than the options allow before any pixel is decoded.

#include <mvcl/model/Texture.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace mvcl::gltf {

class GltfImageDecoder {
public:
    /// `maxPixels` per image; `maxTotalBytes` for all images of the file with their mip chains.
    GltfImageDecoder(std::uint64_t maxPixels, std::uint64_t maxTotalBytes)
        : m_maxPixels(maxPixels), m_maxTotalBytes(maxTotalBytes) {}

    /// The decoded image, or nullptr with `problem` set (never throws for bad image data).
    std::shared_ptr<const TextureImage> decode(std::span<const std::uint8_t> bytes, const std::string &name,
                                               TextureColorSpace space, std::string &problem);

    std::size_t bytesUsed() const { return m_bytesUsed; }

    /// "PNG", "JPEG", "KTX2", "WebP", ... from the first bytes; "" when unknown.
    static std::string formatOf(std::span<const std::uint8_t> bytes);

private:
    std::uint64_t m_maxPixels;
    std::uint64_t m_maxTotalBytes;
    std::size_t m_bytesUsed = 0;
};

} // namespace mvcl::gltf
