#pragma once
/// \file FrameWriter.h
/// Where the frames of an animation or a recording go: numbered image files
/// ("frames/%04d.png": one printf-style frame number, %d or %0Nd, and any extension writeImage
/// knows) or one H.264 video file (.mp4, .mkv, .mov), encoded by the optional FFmpeg module
/// mvcl-video-ffmpeg.so, loaded the first time a video is opened from the plugin search path
/// (as the OpenImageIO module is; see ImageIO.h).
///
/// Each image file is written atomically (a temporary file, then rename), so a render that
/// stops half-way leaves every frame it finished intact and no torn file.

#include <mvcl/core/Export.h>

#include <mvcl/view/Framebuffer.h>

#include <memory>
#include <string>

namespace mvcl {

class MVCL_EXPORT FrameWriter {
public:
    /// Checks what can be checked before anything renders, and throws mvcl::Error(target,
    /// problem) for it: a pattern without exactly one frame number, a folder that cannot be
    /// created or written, a video without the FFmpeg module (or one it cannot create).
    FrameWriter(const std::string &target, int width, int height, double frameRate);
    /// Finishes a video, ignoring errors (call finish() to see them).
    ~FrameWriter();
    FrameWriter(const FrameWriter &) = delete;
    FrameWriter &operator=(const FrameWriter &) = delete;

    /// Whether `target` names a video file (by its extension) rather than numbered images.
    static bool isVideo(const std::string &target);
    /// The file of frame `frame` for a pattern such as "frames/%04d.png" (unchecked pattern:
    /// text after the first frame number is kept as it is).
    static std::string frameFileName(const std::string &pattern, int frame);

    const std::string &target() const;
    bool writesVideo() const;

    /// Writes frame `frame` (images: its number names the file; a video takes frames in the
    /// order given, at the frame rate). The image must have the size given at construction.
    /// Throws mvcl::Error naming the file.
    void write(int frame, const Framebuffer &image);
    /// Finishes a video file (flushes the encoder, writes the index); nothing for images.
    /// Throws mvcl::Error naming the file.
    void finish();

private:
    struct MVCL_HIDDEN Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
