#pragma once
/// \file ImageIO.h
/// Image files through OpenImageIO. 8-bit formats (.png, .jpg, .tif) are written sRGB-encoded;
/// float formats (.exr, .hdr) stay linear.

#include <mvcl/view/Framebuffer.h>

#include <filesystem>

namespace mvcl {

/// Writes the image; creates the parent folder. Throws mvcl::Error naming the file.
void writeImage(const std::filesystem::path &path, const Framebuffer &image);

/// Reads an image back into linear RGB (sRGB-decoding 8-bit files). Throws mvcl::Error.
Framebuffer readImage(const std::filesystem::path &path);

float linearToSrgb(float linear);
float srgbToLinear(float encoded);

} // namespace mvcl
