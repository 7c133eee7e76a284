#pragma once
/// \file ViewLensContext.h
/// The LensContext of a view: what a render of `scene` through `camera` at width × height
/// passes to its lenses (RenderSession does the same). Tools that compose a stack outside a
/// render session (PixelProbe, depth histograms, tests) use it so that lenses that depend on the
/// view or the scene behave as they do in the image.
///
///     const PolicyMap map = stack.compose(lensContextOf(scene, camera, 320, 240), base);

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensContext.h>

namespace mvcl {

class Camera;
struct Scene;

MVCL_EXPORT LensContext lensContextOf(const Scene &scene, const Camera &camera, int width, int height);

} // namespace mvcl
