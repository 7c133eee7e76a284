#pragma once
/// \file LensOutlines.h
/// The "outline" join: after rendering, each enabled lens with an outline width draws its
/// boundary over the image, bottom → top, anti-aliased by distance.

#include <mvcl/core/Export.h>

namespace mvcl {

class LensStack;
class Framebuffer;

MVCL_EXPORT void drawLensOutlines(const LensStack &stack, Framebuffer &image);
/// A view in compare mode (RenderSession::setLensStacks): each stack's outlines only on its
/// side of the divider, and the divider as a one-pixel white line left of column
/// round(dividerX · width).
MVCL_EXPORT void drawLensOutlines(const LensStack &left, const LensStack &right, float dividerX, Framebuffer &image);

} // namespace mvcl
