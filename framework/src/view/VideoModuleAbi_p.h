#pragma once
/// \file VideoModuleAbi_p.h
/// Private to FrameWriter.cpp and the optional video module mvcl-video-ffmpeg.so
/// (framework/video-ffmpeg): the C interface between them. FrameWriter dlopens the module the
/// first time a video file is written and calls its entry point `mvcl_video_module`. Plain C
/// types only: the module links FFmpeg's libraries and nothing of mvcl, and no exception or C++
/// object crosses the boundary. FFmpeg loads some 130 shared libraries (codecs, containers),
/// which no process should pay for unless it writes a video.

#include <cstdint>

extern "C" {

#define MVCL_VIDEO_MODULE_SYMBOL "mvcl_video_module"
#define MVCL_VIDEO_MODULE_ABI 1u

struct MvclVideoModule {
    std::uint32_t abiVersion; ///< MVCL_VIDEO_MODULE_ABI of the module's build
    std::uint32_t size;       ///< sizeof(MvclVideoModule) of the module's build

    /// Creates `path` (the container from its extension) for H.264 video of width × height at
    /// frameRateNumerator / frameRateDenominator frames per second. Returns the open video, or
    /// null and sets *error (valid until the module's next call on this thread).
    void *(*open)(const char *path, int width, int height, int frameRateNumerator, int frameRateDenominator,
                  const char **error);
    /// Encodes one frame: width × height RGB pixels, 8 bits a channel, sRGB-encoded, rows top
    /// first. Returns nullptr, or what went wrong.
    const char *(*write)(void *video, const unsigned char *rgb);
    /// Flushes the encoder, finishes the file and frees `video` (also after an error). Returns
    /// nullptr, or what went wrong.
    const char *(*close)(void *video);
};

typedef const MvclVideoModule *(*MvclVideoModuleEntry)();

} // extern "C"
