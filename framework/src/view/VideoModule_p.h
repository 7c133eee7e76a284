#pragma once
/// \file VideoModule_p.h
/// Private to FrameWriter.cpp (and its tests): finding and loading the optional FFmpeg module
/// mvcl-video-ffmpeg.so, which encodes videos.

#include "VideoModuleAbi_p.h"

#include <filesystem>
#include <string>
#include <vector>

namespace mvcl::detail {

/// The module's name; its file is <name>.so.
inline constexpr const char *kFfmpegVideoModule = "mvcl-video-ffmpeg";

/// Loads the module from the first of `directories` that has it (never unloaded). Throws
/// mvcl::Error naming `file` when there is none ("a video needs the FFmpeg module ..., which was
/// not found ..."), or when it cannot be loaded or was built for another interface.
const MvclVideoModule &loadVideoModule(const std::string &file, const std::vector<std::filesystem::path> &directories);

} // namespace mvcl::detail
