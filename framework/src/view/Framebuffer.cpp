#include <mvcl/view/Framebuffer.h>

namespace mvcl {

Framebuffer::Framebuffer(int width, int height)
    : m_width(width), m_height(height), m_pixels(std::size_t(width) * std::size_t(height)) {}

} // namespace mvcl
