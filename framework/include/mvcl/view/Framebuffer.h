#pragma once
/// \file Framebuffer.h
/// Linear-light RGB float image, row-major, row 0 at the top.

#include <mvcl/core/Export.h>

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace mvcl {

class MVCL_EXPORT Framebuffer {
public:
    Framebuffer() = default;
    Framebuffer(int width, int height);

    int width() const { return m_width; }
    int height() const { return m_height; }
    glm::vec3 &at(int x, int y) { return m_pixels[std::size_t(y) * m_width + x]; }
    const glm::vec3 &at(int x, int y) const { return m_pixels[std::size_t(y) * m_width + x]; }
    const std::vector<glm::vec3> &pixels() const { return m_pixels; }
    std::vector<glm::vec3> &pixels() { return m_pixels; }

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<glm::vec3> m_pixels;
};

} // namespace mvcl
