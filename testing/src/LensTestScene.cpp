#include <mvcl/testing/LensTestScene.h>

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/view/Renderer.h>
#include <mvcl/view/RenderSettings.h>
#include <mvcl/view/ViewLensContext.h>

#include <string>
#include <utility>

namespace mvcl::test {

struct LensTestScene::Data {
    // The tracer keeps a reference to the scene: both live here, never move.
    Scene scene;
    Tracer tracer;
    Camera camera;
    int width;
    int height;

    Data(Scene s, int w, int h) : scene(std::move(s)), tracer(scene), camera(firstCamera(scene, w, h)), width(w), height(h) {}

    static Camera firstCamera(const Scene &scene, int width, int height) {
        if (width <= 0 || height <= 0)
            throw Error("lens test scene", "the image size must be positive, not " + std::to_string(width) + "×" +
                                               std::to_string(height));
        if (!scene.cameras.empty()) return Camera::fromDesc(scene.cameras.front());
        return Camera::framing(scene.bounds(), 45.f, float(width) / float(height));
    }
};

LensTestScene LensTestScene::builtin(std::string_view name, int width, int height) {
    return LensTestScene(loadScene("builtin:" + std::string(name)), width, height);
}

LensTestScene LensTestScene::load(const std::filesystem::path &source, int width, int height) {
    return LensTestScene(loadScene(source.string()), width, height);
}

LensTestScene::LensTestScene(Scene scene, int width, int height)
    : d(std::make_unique<Data>(std::move(scene), width, height)) {}

LensTestScene::LensTestScene(LensTestScene &&) noexcept = default;
LensTestScene &LensTestScene::operator=(LensTestScene &&) noexcept = default;
LensTestScene::~LensTestScene() = default;

const Scene &LensTestScene::scene() const { return d->scene; }
const Tracer &LensTestScene::tracer() const { return d->tracer; }
const Camera &LensTestScene::camera() const { return d->camera; }
void LensTestScene::setCamera(const Camera &camera) { d->camera = camera; }
int LensTestScene::width() const { return d->width; }
int LensTestScene::height() const { return d->height; }

LensContext LensTestScene::context() const { return lensContextOf(d->scene, d->camera, d->width, d->height); }

LensTestScene::Probe LensTestScene::probe(const LensStack &stack, const RayPolicy &base) const {
    return Probe(*d, PixelProbe(stack, context(), base));
}

Framebuffer LensTestScene::render(const LensStack &stack, int samplesPerPixel, const RayPolicy &base) const {
    RenderSettings settings;
    settings.width = d->width;
    settings.height = d->height;
    settings.samplesPerPixel = samplesPerPixel;
    Framebuffer image;
    Renderer(d->tracer).render(d->camera, stack.compose(context(), base), settings, image);
    return image;
}

std::optional<Hit> LensTestScene::Probe::primaryHit(int x, int y) const {
    return m_probe.primaryHit(m_data->tracer, m_data->camera, x, y);
}

std::optional<int> LensTestScene::Probe::primaryHitLayer(int x, int y) const {
    return m_probe.primaryHitLayer(m_data->tracer, m_data->camera, x, y);
}

PickResult LensTestScene::Probe::pick(int x, int y) const { return m_probe.pick(m_data->tracer, m_data->camera, x, y); }

glm::vec3 LensTestScene::Probe::radiance(int x, int y) const {
    return m_probe.radiance(m_data->tracer, m_data->camera, x, y);
}

} // namespace mvcl::test
