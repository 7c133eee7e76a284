#include "ImageTexture.h"

#include <mvcl/view/ImageIO.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

namespace mvcl::viewer {

ImageTexture::ImageTexture() {
    for (size_t i = 0; i < m_srgb.size(); ++i)
        m_srgb[i] = uint8_t(std::lround(linearToSrgb(float(i) / float(m_srgb.size() - 1)) * 255.f));
    glGenTextures(1, &m_texture);
    glBindTexture(GL_TEXTURE_2D, m_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0); // no mipmaps
}

ImageTexture::~ImageTexture() { glDeleteTextures(1, &m_texture); }

void ImageTexture::update(const Framebuffer &image, const PixelRect &changed) {
    m_lastUploadPixels = 0;
    glBindTexture(GL_TEXTURE_2D, m_texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    PixelRect rect = changed;
    if (image.width() != m_width || image.height() != m_height) {
        m_width = image.width();
        m_height = image.height();
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, m_width, m_height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        rect = {0, 0, m_width, m_height};
    }
    rect = {std::max(rect.x0, 0), std::max(rect.y0, 0), std::min(rect.x1, m_width), std::min(rect.y1, m_height)};
    if (rect.isEmpty()) return;
    const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
    m_staging.resize(size_t(w) * size_t(h) * 4);
    const float steps = float(m_srgb.size() - 1);
    uint8_t *out = m_staging.data();
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; ++x) {
            const glm::vec3 &c = image.at(x, y);
            for (int k = 0; k < 3; ++k) {
                const float v = c[k] > 0.f ? std::min(c[k], 1.f) : 0.f; // NaN → 0
                *out++ = m_srgb[size_t(v * steps + 0.5f)];
            }
            *out++ = 255;
        }
    // RGBA: uploads of 8-bit RGBA into an RGBA8 texture are a plain copy in the drivers; RGB is converted.
    glTexSubImage2D(GL_TEXTURE_2D, 0, rect.x0, rect.y0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, m_staging.data());
    m_lastUploadPixels = uint64_t(w) * uint64_t(h);
}

} // namespace mvcl::viewer
