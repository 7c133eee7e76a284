#pragma once
/// \file WhittedIntegrator.h
/// The paper's integrator: Phong (eq. 1) + shadows + mirror reflection + refraction (Snell, total
/// internal reflection, Schlick's Fresnel), bounded depth, background colour. Shadows pass
/// through transparent occluders scaled by their transparency (colourless). Driven per pixel by
/// a RayPolicy (plain data).

#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayCounters.h>
#include <mvcl/tracer/RayPolicy.h>

#include <glm/vec3.hpp>

namespace mvcl {

class Tracer;

class WhittedIntegrator {
public:
    explicit WhittedIntegrator(const Tracer &tracer);

    /// Linear RGB radiance along a primary ray under `policy` (colour stage included).
    glm::vec3 radiance(const Ray &primaryRay, const RayPolicy &policy, RayCounters &counters) const;

private:
    glm::vec3 trace(const Ray &ray, RayType type, int depth, const RayPolicy &policy,
                    RayCounters &counters) const;

    /// Share of a light's intensity (0..1) that reaches the shadow ray's origin.
    float lightPassing(const Ray &shadowRay, float lightDistance, const RayPolicy &policy,
                       RayCounters &counters) const;

    const Tracer &m_tracer;
    bool m_hasTransparentMaterials = false;
};

} // namespace mvcl
