// WhittedIntegrator::outlineCoverage: the Outlines mode of the edge lines (EdgeLineMode), kept
// apart from the lighting in WhittedIntegrator.cpp.

#include <mvcl/tracer/WhittedIntegrator.h>

#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/SurfaceInteraction.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <array>
#include <cmath>

namespace mvcl {

namespace {

/// Two unit vectors perpendicular to unit `n` and to each other, without a branch that flips
/// between neighbouring rays (Duff et al.'s orthonormal basis).
std::array<glm::vec3, 2> perpendicularPair(const glm::vec3 &n) {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z), b = n.x * n.y * a;
    return {glm::vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x), glm::vec3(b, sign + n.y * n.y * a, -n.y)};
}

// A probe that meets the same surface farther than this share of the distance from where the
// surface's plane predicts has found a fold of the surface in front of or behind itself.
constexpr float kDepthJump = 0.05f;

} // namespace

float WhittedIntegrator::outlineCoverage(const Ray &ray, const RayQuery &query, const Hit *hit,
                                         const EdgePolicy &edges, RayCounters &counters) const {
    // One pixel spans coneSpread radians; probes half a line width to either side see what the
    // line straddles. Without a cone (a thin ray) there is no pixel to measure lines in.
    const float offset = 0.5f * edges.widthPixels * ray.coneSpread;
    if (!(offset > 0.f)) return 0.f;
    const glm::vec3 d = glm::normalize(ray.direction);
    const std::array<glm::vec3, 2> across = perpendicularPair(d);
    SurfaceInteraction si;
    if (hit) si = m_tracer.interaction(ray, *hit);
    const float cosCrease = std::cos(glm::radians(edges.creaseDegrees));
    for (const glm::vec3 &side : {across[0], -across[0], across[1], -across[1]}) {
        const Ray probe{ray.origin, d + offset * side};
        ++counters.primary;
        Hit probeHit;
        const bool probeHits = closestVisibleHit(probe, query, probeHit);
        if (!hit || !probeHits) {
            if (probeHits != (hit != nullptr)) return 1.f; // a silhouette against the background
            continue;
        }
        if (probeHit.kind != hit->kind || probeHit.geometry != hit->geometry) return 1.f; // another mesh
        const SurfaceInteraction probeSi = m_tracer.interaction(probe, probeHit);
        if (glm::dot(probeSi.shadingNormal, si.shadingNormal) < cosCrease) return 1.f; // a crease
        const float towardPlane = glm::dot(probe.direction, si.geometricNormal);
        if (std::abs(towardPlane) > 1e-6f) {
            const float planeT = glm::dot(si.position - probe.origin, si.geometricNormal) / towardPlane;
            if (std::abs(probeHit.t - planeT) * glm::length(probe.direction) >
                kDepthJump * hit->t * glm::length(ray.direction))
                return 1.f; // the same mesh folding over itself
        }
    }
    return 0.f;
}

} // namespace mvcl
