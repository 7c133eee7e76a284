#pragma once
/// \file ImageIO.h
/// Image files, the format chosen by the extension (case-insensitive). Built in: .png, .jpg/.jpeg,
/// .tga, .bmp (stb; 8-bit, sRGB-encoded), .hdr (stb) and .exr (tinyexr; 32-bit float, ZIP), both
/// linear float. Every other extension (.tif, ...) goes to the optional OpenImageIO module
/// mvcl-imageio-oiio.so (8-bit sRGB), loaded the first time such a file is written or read, from
/// the plugin search path (LensRegistry::defaultSearchPath()) or the plugin folder beside
/// libmvcl.so; without it those files fail with an mvcl::Error that names the module.

#include <mvcl/core/Export.h>

#include <mvcl/view/Framebuffer.h>

#include <filesystem>

namespace mvcl {

/// Writes the image; creates the parent folder. Writes a temporary file beside it and renames
/// it, so a failed write leaves an older file as it was. Throws mvcl::Error naming the file.
MVCL_EXPORT void writeImage(const std::filesystem::path &path, const Framebuffer &image);

/// Reads an image back into linear RGB (sRGB-decoding 8-bit files). Throws mvcl::Error.
MVCL_EXPORT Framebuffer readImage(const std::filesystem::path &path);

MVCL_EXPORT float linearToSrgb(float linear);
MVCL_EXPORT float srgbToLinear(float encoded);

} // namespace mvcl
