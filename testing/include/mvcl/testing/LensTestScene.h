#pragma once
/// \file LensTestScene.h
/// A scene to unit-test lenses on, part of mvcl::testing: build a small one or load one, put a
/// stack on it, and ask per pixel what happens — the composed policy, the lenses covering the
/// pixel and their weights, the primary hit and its layer, the radiance — with public headers
/// only. Lenses contribute as they do in a render of this scene and view (lensContextOf()), so
/// lenses that depend on the camera or the scene behave as they do in an image.
///
///     const LensTestScene scene = LensTestScene::builtin("cube-in-cube", 64, 48);
///     LensStack stack;
///     stack.add(lens);                                       // lens 0
///     const LensTestScene::Probe probe = scene.probe(stack);
///     EXPECT_FLOAT_EQ(probe.lensWeight(0, 32, 24), 1.f);       // the lens covers the centre
///     EXPECT_EQ(probe.primaryHitLayer(32, 24), 1);             // and shows layer 1 there
///     EXPECT_GT(probe.radiance(32, 24).r, probe.radiance(32, 24).b);
///
/// The scene, its tracer and camera are built once and read-only afterwards: probes and renders
/// may run on any number of threads.

#include <mvcl/lens/LensContext.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/RayPolicy.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/Framebuffer.h>
#include <mvcl/view/Picking.h>
#include <mvcl/view/PixelProbe.h>

#include <glm/vec3.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace mvcl::test {

class LensTestScene {
    struct Data;

public:
    /// A built-in scene ("cube-in-cube", ...: builtinSceneNames()) seen through its first
    /// camera at width × height pixels. Throws mvcl::Error for an unknown name or a bad size.
    static LensTestScene builtin(std::string_view name = "cube-in-cube", int width = 64, int height = 48);
    /// A model file (.gltf, .glb) or any source loadScene() takes; its first camera, or one
    /// framing the scene when it has none. Throws mvcl::Error naming the file and the problem.
    static LensTestScene load(const std::filesystem::path &source, int width = 64, int height = 48);
    /// Takes `scene` over; first camera or a framing one, as load().
    LensTestScene(Scene scene, int width, int height);

    LensTestScene(LensTestScene &&) noexcept;
    LensTestScene &operator=(LensTestScene &&) noexcept;
    ~LensTestScene();

    const Scene &scene() const;
    const Tracer &tracer() const;
    const Camera &camera() const;
    void setCamera(const Camera &camera);
    int width() const;
    int height() const;
    /// What a render of this view passes to lenses: camera, size, bounds, origin, layers.
    LensContext context() const;

    /// What a stack does to each pixel of this view.
    class Probe {
    public:
        const PixelProbe &pixels() const { return m_probe; }
        /// The composed policy map (width × height).
        const PolicyMap &map() const { return m_probe.map(); }
        /// The pixel's dominant policy: what its ray does (visibility, shading, colour, shaping).
        const PixelPolicy &policy(int x, int y) const { return m_probe.policy(x, y); }
        /// Share of the pixel lens `lensIndex` (stack index, bottom first) covers, 0..1.
        float lensWeight(int lensIndex, int x, int y) const { return m_probe.lensWeight(lensIndex, x, y); }
        /// Every lens over the pixel with its weight, bottom first.
        std::vector<LensWeight> lenses(int x, int y) const { return m_probe.lenses(x, y); }
        /// The primary ray's hit under the pixel's policy, nullopt for a miss.
        std::optional<Hit> primaryHit(int x, int y) const;
        /// Layer of the mesh the primary ray hits (-1 for spheres and planes), nullopt for a miss.
        std::optional<int> primaryHitLayer(int x, int y) const;
        /// Names, distance and positions of the primary hit (Picking.h).
        PickResult pick(int x, int y) const;
        /// Linear RGB of one sample through the pixel centre, blended over the pixel's policies.
        glm::vec3 radiance(int x, int y) const;

    private:
        friend class LensTestScene;
        Probe(const Data &data, PixelProbe probe) : m_data(&data), m_probe(std::move(probe)) {}
        const Data *m_data;
        PixelProbe m_probe;
    };

    /// The stack composed over `base` in this view. The probe refers to this scene's tracer and
    /// camera as they are now: keep the scene alive while it is used.
    Probe probe(const LensStack &stack, const RayPolicy &base = {}) const;
    /// The image of the stack over `base`: `samplesPerPixel` samples per pixel, same seed every
    /// time (so two renders of equal stacks are equal).
    Framebuffer render(const LensStack &stack, int samplesPerPixel = 1, const RayPolicy &base = {}) const;

private:
    std::unique_ptr<Data> d;
};

} // namespace mvcl::test
