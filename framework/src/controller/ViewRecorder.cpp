#include <mvcl/controller/ViewRecorder.h>

#include <mvcl/core/Error.h>

#include <cmath>

namespace mvcl {

ViewRecorder::ViewRecorder(const std::string &target, const glm::ivec2 &size, double frameRate)
    : m_writer(target, size.x, size.y, frameRate), m_size(size), m_frameRate(frameRate) {}

void ViewRecorder::addImage(double seconds, const Framebuffer &image) {
    if (image.width() != m_size.x || image.height() != m_size.y)
        throw Error(m_writer.target(), "the view changed size while recording (" + std::to_string(m_size.x) + "x" +
                                           std::to_string(m_size.y) + " at the start): recording stopped");
    // Frames 0 … floor(seconds · rate) are due; the small tolerance keeps a time of exactly
    // i / rate, computed in floating point, from falling a frame short.
    const int due = int(std::floor(seconds * m_frameRate + 1e-9)) + 1;
    while (m_framesWritten < due) m_writer.write(m_framesWritten++, image);
}

void ViewRecorder::finish() { m_writer.finish(); }

} // namespace mvcl
