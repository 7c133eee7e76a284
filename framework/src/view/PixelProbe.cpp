#include <mvcl/view/PixelProbe.h>

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>
#include <mvcl/view/Camera.h>

namespace mvcl {

namespace {

Ray primaryRay(const PixelPolicy &policy, const Camera &camera, int x, int y, int width, int height) {
    const glm::vec2 sample = policy.samplePosition({float(x) + 0.5f, float(y) + 0.5f}, width, height);
    return camera.generateRay(sample.x, sample.y, width, height);
}

} // namespace

PixelProbe::PixelProbe(const LensStack &stack, int width, int height, const RayPolicy &base)
    : m_map(stack.compose(base, width, height)) {}

std::optional<Hit> PixelProbe::primaryHit(const Tracer &tracer, const Camera &camera, int x, int y) const {
    const PixelPolicy &p = policy(x, y);
    Hit hit;
    if (!tracer.closestHit(primaryRay(p, camera, x, y, m_map.width(), m_map.height()),
                           p.ray.query(RayType::Primary), hit))
        return std::nullopt;
    return hit;
}

std::optional<int> PixelProbe::primaryHitLayer(const Tracer &tracer, const Camera &camera, int x, int y) const {
    const std::optional<Hit> hit = primaryHit(tracer, camera, x, y);
    if (!hit) return std::nullopt;
    return hit->kind == GeometryKind::Triangle ? int(tracer.scene().meshes[hit->geometry].layer) : -1;
}

glm::vec3 PixelProbe::radiance(const Tracer &tracer, const Camera &camera, int x, int y) const {
    const WhittedIntegrator integrator(tracer);
    RayCounters rays;
    glm::vec3 sum(0.f);
    for (const PolicyTerm &term : m_map.terms(x, y)) {
        const PixelPolicy &p = m_map.policy(term.policy);
        sum += term.weight * integrator.radiance(primaryRay(p, camera, x, y, m_map.width(), m_map.height()), p.ray, rays);
    }
    return sum;
}

} // namespace mvcl
