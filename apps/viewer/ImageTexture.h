#pragma once
// The rendered image as one OpenGL texture: allocated once per image size (no mipmaps), then
// only the rectangles the render session reports as changed are converted to 8-bit sRGB and
// uploaded.

#include <mvcl/lens/LensRegion.h>
#include <mvcl/view/Framebuffer.h>

#include <array>
#include <cstdint>
#include <vector>

namespace mvcl::viewer {

class ImageTexture {
public:
    ImageTexture();
    ~ImageTexture();
    ImageTexture(const ImageTexture &) = delete;
    ImageTexture &operator=(const ImageTexture &) = delete;

    /// Uploads `changed` of `image` (linear RGB); reallocates only when the size differs.
    void update(const Framebuffer &image, const PixelRect &changed);

    unsigned glName() const { return m_texture; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// Pixels uploaded by the last update (for the stats panel).
    uint64_t lastUploadPixels() const { return m_lastUploadPixels; }

private:
    unsigned m_texture = 0;
    int m_width = 0;
    int m_height = 0;
    uint64_t m_lastUploadPixels = 0;
    std::vector<uint8_t> m_staging;
    /// Linear [0, 1] in 4096 steps → sRGB byte: the conversion of a full frame stays a few ms.
    std::array<uint8_t, 4097> m_srgb{};
};

} // namespace mvcl::viewer
