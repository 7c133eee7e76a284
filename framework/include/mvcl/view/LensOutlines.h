#pragma once
/// \file LensOutlines.h
/// The "outline" join: after rendering, each enabled lens with an outline width draws its
/// boundary over the image, bottom → top, anti-aliased by distance.

#include <mvcl/core/Export.h>

namespace mvcl {

class LensStack;
class Framebuffer;

MVCL_EXPORT void drawLensOutlines(const LensStack &stack, Framebuffer &image);

} // namespace mvcl
