#include "GltfImageDecoder_p.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

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
    // OpenImageIO picks the reader from the name's extension and reads through the proxy only:
    // nothing is opened on disk.
    OIIO::Filesystem::IOMemReader reader(const_cast<std::uint8_t *>(bytes.data()), bytes.size());
    const std::string virtualName = format == "PNG" ? "texture.png" : "texture.jpg";
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1); // glTF alpha is straight, not premultiplied
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create(format == "PNG" ? "png" : "jpeg", false, nullptr, &reader);
    OIIO::ImageSpec spec;
    if (!in || !in->set_ioproxy(&reader) || !in->open(virtualName, spec, config)) {
        problem = "cannot be decoded as " + format + ": " + (in ? in->geterror() : OIIO::geterror());
        return nullptr;
    }
    const std::uint64_t width = std::uint64_t(std::max(spec.width, 0));
    const std::uint64_t height = std::uint64_t(std::max(spec.height, 0));
    const int channels = spec.nchannels;
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
    const int readChannels = std::min(channels, 4);
    std::vector<std::uint8_t> raw;
    try {
        raw.resize(std::size_t(width * height) * std::size_t(readChannels));
    } catch (const std::bad_alloc &) {
        problem = "does not fit in memory";
        return nullptr;
    }
    if (!in->read_image(0, 0, 0, readChannels, OIIO::TypeDesc::UINT8, raw.data())) {
        problem = "cannot be decoded as " + format + ": " + in->geterror();
        return nullptr;
    }
    in->close();
    // Grey, grey + alpha, RGB and RGBA all become RGBA.
    std::vector<std::uint8_t> rgba(std::size_t(width * height) * 4);
    for (std::size_t i = 0; i < std::size_t(width * height); ++i) {
        const std::uint8_t *p = raw.data() + i * std::size_t(readChannels);
        std::uint8_t *q = rgba.data() + i * 4;
        if (readChannels <= 2) {
            q[0] = q[1] = q[2] = p[0];
            q[3] = readChannels == 2 ? p[1] : 255;
        } else {
            q[0] = p[0];
            q[1] = p[1];
            q[2] = p[2];
            q[3] = readChannels == 4 ? p[3] : 255;
        }
    }
    auto image = std::make_shared<const TextureImage>(name, int(width), int(height), std::move(rgba), space);
    m_bytesUsed += image->memoryBytes();
    return image;
}

} // namespace mvcl::gltf
