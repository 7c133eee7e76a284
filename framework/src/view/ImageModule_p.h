#pragma once
/// \file ImageModule_p.h
/// Private to ImageIO.cpp (and its tests): finding and loading the optional OpenImageIO module
/// mvcl-imageio-oiio.so, which writes and reads the formats without a built-in codec.

#include "ImageModuleAbi_p.h"

#include <filesystem>
#include <string>
#include <vector>

namespace mvcl::detail {

/// The module's name; its file is <name>.so.
inline constexpr const char *kOiioImageModule = "mvcl-imageio-oiio";

/// Where the module is looked for: LensRegistry::defaultSearchPath() ($MVCL_PLUGIN_PATH, the
/// executable's directory, <exe dir>/../lib/mvcl/plugins), then the plugin directory beside
/// libmvcl.so itself (for programs outside an mvcl build or install tree).
std::vector<std::filesystem::path> imageModuleSearchPath();

/// The first of `directories` that holds `moduleFile`, as an absolute path, or empty; `searched`
/// gets the directories looked in, for the message that says it is missing. Shared with the
/// video module (FrameWriter.cpp), which is looked for in the same places.
std::filesystem::path findModuleFile(const std::string &moduleFile, const std::vector<std::filesystem::path> &directories,
                                     std::string &searched);

/// Loads the module from the first of `directories` that has it (never unloaded). Throws
/// mvcl::Error naming `file` when there is none ("the .tif format needs the OpenImageIO module
/// mvcl-imageio-oiio, ..."), or when it cannot be loaded or was built for another interface.
const MvclImageModule &loadImageModule(const std::string &file, const std::vector<std::filesystem::path> &directories);

} // namespace mvcl::detail
