#include <mvcl/view/ViewLensContext.h>

#include <mvcl/model/Scene.h>
#include <mvcl/view/Camera.h>

namespace mvcl {

LensContext lensContextOf(const Scene &scene, const Camera &camera, int width, int height) {
    LensContext context = LensContext::forScene(scene);
    context.camera = {"", camera.eye(), camera.target(), camera.up(), camera.verticalFovDegrees()};
    context.imageWidth = width;
    context.imageHeight = height;
    return context;
}

} // namespace mvcl
