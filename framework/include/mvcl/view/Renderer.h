#pragma once
/// \file Renderer.h
/// One-shot frames: every pixel gets RenderSettings::samplesPerPixel samples, tile-parallel on
/// the worker pool. Each pixel's samples depend only on (x, y, sample index, seed), and a pixel
/// is summed in a fixed order, so the image is identical for any thread count, and identical
/// to a RenderSession's Fixed-mode image of the same settings. Interactive views (incremental,
/// progressive, adaptive) use RenderSession.

#include <mvcl/core/Export.h>

#include <mvcl/lens/PolicyMap.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/Framebuffer.h>
#include <mvcl/view/RenderSettings.h>
#include <mvcl/view/RenderStats.h>

#include <functional>

namespace mvcl {

class Tracer;

/// Called with the fraction done (0..1), from whichever thread finished a tile, serialised.
using ProgressCallback = std::function<void(float)>;

class MVCL_EXPORT Renderer {
public:
    explicit Renderer(const Tracer &tracer);

    /// Renders into `target` (resized to settings.width × settings.height). `policies` must have
    /// the same size; a pixel blending several policies (a feathered lens edge) renders each
    /// and blends the radiance by weight. Thread-safe with respect to other renders of the
    /// same tracer.
    RenderStats render(const Camera &camera, const PolicyMap &policies,
                       const RenderSettings &settings, Framebuffer &target,
                       const ProgressCallback &progress = {}) const;

    /// Throws mvcl::Error when the settings are out of range or do not match the map's size.
    static void checkSettings(const RenderSettings &settings, const PolicyMap &policies);

private:
    const Tracer &m_tracer;
};

} // namespace mvcl
