#pragma once
// Small renders for tests (renderer, robustness): one policy for the whole image, plus image metrics
// (bitwise hash, mean absolute difference, non-finite pixels).

#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/Renderer.h>

#include <glm/vec3.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace mvcl::test {

struct TestRender {
    Framebuffer image;
    RenderStats stats;
};

inline TestRender renderWithPolicy(const Tracer &tracer, const Camera &camera, int width, int height,
                                         int spp, int threads, const RayPolicy &policy = {}) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.samplesPerPixel = spp;
    settings.threads = threads;
    TestRender out;
    out.stats = Renderer(tracer).render(camera, PolicyMap(width, height, policy), settings, out.image);
    return out;
}

/// FNV-1a over the pixels' float bits: equal hashes ⇔ (practically) bit-identical images.
inline uint64_t framebufferHash(const Framebuffer &f) {
    uint64_t h = 1469598103934665603ull;
    for (const glm::vec3 &p : f.pixels())
        for (int c = 0; c < 3; ++c) {
            h ^= std::bit_cast<uint32_t>(p[c]);
            h *= 1099511628211ull;
        }
    return h;
}

inline std::size_t nonFinitePixels(const Framebuffer &f) {
    std::size_t n = 0;
    for (const glm::vec3 &p : f.pixels())
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) ++n;
    return n;
}

/// Mean over pixels and channels of |a − b| (linear radiance); 1e30 if the sizes differ.
inline double meanAbsDifference(const Framebuffer &a, const Framebuffer &b) {
    if (a.width() != b.width() || a.height() != b.height() || a.pixels().empty()) return 1e30;
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) sum += std::fabs(double(a.pixels()[i][c]) - double(b.pixels()[i][c]));
    return sum / double(3 * a.pixels().size());
}

} // namespace mvcl::test
