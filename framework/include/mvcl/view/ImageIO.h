#pragma once
/// \file ImageIO.h
/// Image files through OpenImageIO. 8-bit formats (.png, .jpg, .tif) are written sRGB-encoded;
/// float formats (.exr, .hdr) stay linear.

#include <mvcl/core/Export.h>

#include <mvcl/view/Framebuffer.h>

#include <filesystem>

namespace mvcl {

/// Writes the image; creates the parent folder. Throws mvcl::Error naming the file.
MVCL_EXPORT void writeImage(const std::filesystem::path &path, const Framebuffer &image);

/// Reads an image back into linear RGB (sRGB-decoding 8-bit files). Throws mvcl::Error.
MVCL_EXPORT Framebuffer readImage(const std::filesystem::path &path);

MVCL_EXPORT float linearToSrgb(float linear);
MVCL_EXPORT float srgbToLinear(float encoded);

} // namespace mvcl
