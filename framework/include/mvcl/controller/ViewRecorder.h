#pragma once
/// \file ViewRecorder.h
/// Records a view while it is used: the images it shows, at a fixed frame rate, into numbered
/// image files or a video (FrameWriter). The app hands it the view's image whenever it draws one
/// with the time since the recording began; frame i is the image shown at time i / frameRate,
/// so a view that draws slower than the frame rate repeats its image, and one that draws faster
/// skips images. The clock is the caller's, which keeps this testable and free of threads.

#include <mvcl/core/Export.h>

#include <mvcl/view/FrameWriter.h>
#include <mvcl/view/Framebuffer.h>

#include <glm/vec2.hpp>

#include <string>

namespace mvcl {

class MVCL_EXPORT ViewRecorder {
public:
    /// Opens `target` (a pattern such as "rec/%04d.png" or a video file) for images of `size`.
    /// Throws mvcl::Error(target, problem) as FrameWriter does.
    ViewRecorder(const std::string &target, const glm::ivec2 &size, double frameRate);

    double frameRate() const { return m_frameRate; }
    const glm::ivec2 &size() const { return m_size; }
    int framesWritten() const { return m_framesWritten; }

    /// The view shows `image` at `seconds` since the recording began: writes every frame due by
    /// then (at least the first). Throws mvcl::Error when the image is not of the recorded size
    /// (the view was resized) or a frame cannot be written.
    void addImage(double seconds, const Framebuffer &image);
    /// Finishes the file (a video's index). Throws mvcl::Error naming it.
    void finish();

private:
    FrameWriter m_writer;
    glm::ivec2 m_size;
    double m_frameRate;
    int m_framesWritten = 0;
};

} // namespace mvcl
