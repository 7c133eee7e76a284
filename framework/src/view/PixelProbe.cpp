#include <mvcl/view/PixelProbe.h>

#include <mvcl/lens/LensContext.h>

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>
#include <mvcl/view/Camera.h>

namespace mvcl {

PixelProbe::PixelProbe(const LensStack &stack, int width, int height, const RayPolicy &base)
    : m_map(stack.compose(base, width, height)) {}

PixelProbe::PixelProbe(const LensStack &stack, const LensContext &context, const RayPolicy &base)
    : m_map(stack.compose(context, base)) {}

float PixelProbe::lensWeight(int lensIndex, int x, int y) const {
    if (lensIndex < 0 || lensIndex >= 64) return 0.f;
    float weight = 0.f;
    for (const PolicyTerm &term : m_map.terms(x, y))
        if (m_map.policy(term.policy).lensSet & (uint64_t(1) << lensIndex)) weight += term.weight;
    return weight;
}

std::vector<LensWeight> PixelProbe::lenses(int x, int y) const {
    uint64_t present = 0;
    for (const PolicyTerm &term : m_map.terms(x, y))
        if (term.weight > 0.f) present |= m_map.policy(term.policy).lensSet;
    std::vector<LensWeight> result;
    for (int i = 0; i < 64; ++i)
        if (present & (uint64_t(1) << i)) result.push_back({i, lensWeight(i, x, y)});
    return result;
}

std::optional<Hit> PixelProbe::primaryHit(const Tracer &tracer, const Camera &camera, int x, int y) const {
    const PixelPolicy &p = policy(x, y);
    Hit hit;
    if (!tracer.closestHit(pixelCentreRay(camera, p, x, y, m_map.width(), m_map.height()),
                           p.ray.query(RayType::Primary), hit))
        return std::nullopt;
    return hit;
}

std::optional<int> PixelProbe::primaryHitLayer(const Tracer &tracer, const Camera &camera, int x, int y) const {
    const std::optional<Hit> hit = primaryHit(tracer, camera, x, y);
    if (!hit) return std::nullopt;
    return hit->kind == GeometryKind::Triangle ? int(tracer.scene().meshes[hit->geometry].layer) : -1;
}

PickResult PixelProbe::pick(const Tracer &tracer, const Camera &camera, int x, int y) const {
    return mvcl::pick(tracer, camera, m_map, x, y);
}

glm::vec3 PixelProbe::radiance(const Tracer &tracer, const Camera &camera, int x, int y) const {
    const WhittedIntegrator integrator(tracer);
    RayCounters rays;
    glm::vec3 sum(0.f);
    for (const PolicyTerm &term : m_map.terms(x, y)) {
        const PixelPolicy &p = m_map.policy(term.policy);
        sum += term.weight * integrator.radiance(pixelCentreRay(camera, p, x, y, m_map.width(), m_map.height()), p.ray, rays);
    }
    return sum;
}

} // namespace mvcl
