#include <mvcl/tracer/WhittedIntegrator.h>

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/RayOffset.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mvcl {

namespace {

// Hard ceiling on recursion whatever a policy asks for: keeps the stack bounded (facing mirrors).
constexpr int kDepthCeiling = 64;

bool isFinite(const glm::vec3 &c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

/// Schlick's approximation of dielectric Fresnel reflectance. cosTheta is the cosine on the
/// side of the lower index (the larger angle), as Schlick requires.
float schlickFresnel(float cosTheta, float ior) {
    const float r0 = ((1.f - ior) / (1.f + ior)) * ((1.f - ior) / (1.f + ior));
    const float m = std::clamp(1.f - cosTheta, 0.f, 1.f);
    return r0 + (1.f - r0) * m * m * m * m * m;
}

uint32_t materialOf(const Scene &scene, const Hit &hit) {
    switch (hit.kind) {
    case GeometryKind::Triangle: return scene.meshes[hit.geometry].material;
    case GeometryKind::Sphere: return scene.spheres[hit.geometry].material;
    case GeometryKind::Plane: return scene.planes[hit.geometry].material;
    }
    return 0;
}

void countRay(RayType type, RayCounters &counters) {
    switch (type) {
    case RayType::Primary: ++counters.primary; break;
    case RayType::Shadow: ++counters.shadow; break;
    case RayType::Reflection: ++counters.reflection; break;
    case RayType::Refraction: ++counters.refraction; break;
    }
}

} // namespace

WhittedIntegrator::WhittedIntegrator(const Tracer &tracer) : m_tracer(tracer) {
    for (const Material &m : tracer.scene().materials)
        if (m.transparency > 0.f) m_hasTransparentMaterials = true;
}

float WhittedIntegrator::lightPassing(const Ray &shadowRay, float lightDistance,
                                      const RayPolicy &policy, RayCounters &counters) const {
    RayQuery query = policy.query(RayType::Shadow);
    query.tMax = std::min(query.tMax, lightDistance);
    countRay(RayType::Shadow, counters);
    // Opaque scenes need only "is anything in the way" (any-hit, the cheap query).
    if (!m_hasTransparentMaterials) return m_tracer.anyHit(shadowRay, query) ? 0.f : 1.f;

    // Transparent occluders let their transparency through (Whitted's transparent shadows):
    // walk the hits along the same ray, each step starting just past the previous hit.
    constexpr int kMaxOccluders = 16;
    const Scene &scene = m_tracer.scene();
    float passed = 1.f;
    for (int i = 0; i < kMaxOccluders; ++i) {
        Hit hit;
        if (!m_tracer.closestHit(shadowRay, query, hit)) return passed;
        passed *= std::clamp(scene.materials[materialOf(scene, hit)].transparency, 0.f, 1.f);
        if (passed <= 0.f) return 0.f;
        query.tMin = nextFloatUp(hit.t);
        if (query.tMin > query.tMax) return passed;
    }
    return 0.f; // more occluders than we follow: treat the light as blocked
}

glm::vec3 WhittedIntegrator::radiance(const Ray &primaryRay, const RayPolicy &policy,
                                      RayCounters &counters) const {
    glm::vec3 c = trace(primaryRay, RayType::Primary, 0, policy, counters);
    if (!policy.color.isIdentity()) c = policy.color.matrix * c + policy.color.offset;
    // A non-finite sample would poison the whole pixel: it is counted (tests assert the count
    // stays 0) and replaced by black.
    if (isFinite(c)) return c;
    ++counters.nonFiniteSamples;
    return glm::vec3(0.f);
}

glm::vec3 WhittedIntegrator::trace(const Ray &ray, RayType type, int depth,
                                   const RayPolicy &policy, RayCounters &counters) const {
    const Scene &scene = m_tracer.scene();
    countRay(type, counters);
    Hit hit;
    if (!m_tracer.closestHit(ray, policy.query(type), hit)) return scene.background;

    const SurfaceInteraction si = m_tracer.interaction(ray, hit);
    const Material &m = scene.materials[si.material];
    const glm::vec3 d = glm::normalize(ray.direction);

    // Light the side the ray arrived on; remember whether it is entering the surface.
    const bool entering = glm::dot(si.geometricNormal, d) < 0.f;
    const glm::vec3 ng = entering ? si.geometricNormal : -si.geometricNormal;
    glm::vec3 ns = entering ? si.shadingNormal : -si.shadingNormal;
    if (glm::dot(ns, ng) < 0.f) ns = ng;

    // Eq. 1: A + Σ I·(P·(L·N) + Ks·(N·H)^Ps) / D
    glm::vec3 local = m.ambient * scene.ambientLight;
    const ShadingPolicy &shading = policy.shading;
    for (const Light &light : scene.lights) {
        glm::vec3 toLight;
        float distance;
        float attenuation = 1.f;
        if (light.type == LightType::Directional) {
            toLight = -light.direction;
            distance = std::numeric_limits<float>::infinity();
        } else {
            toLight = light.position - si.position;
            distance = glm::length(toLight);
            if (!(distance > 0.f)) continue; // light exactly on the surface
            toLight /= distance;
            attenuation = light.constantAttenuation + light.linearAttenuation * distance +
                          light.quadraticAttenuation * distance * distance;
            if (!(attenuation > 0.f)) continue;
        }
        const float nDotL = glm::dot(ns, toLight);
        if (nDotL <= 0.f || glm::dot(ng, toLight) <= 0.f) continue;

        glm::vec3 transmittance(1.f);
        if (shading.shadows) {
            const Ray shadowRay{offsetRayOrigin(si.position, si.positionError, ng, toLight), toLight};
            const float passed = lightPassing(shadowRay, distance, policy, counters);
            // The blocked share of the light is dimmed by the policy's strength and tint.
            const glm::vec3 blocked = glm::mix(glm::vec3(1.f), shading.shadowTint, shading.shadowStrength);
            transmittance = glm::vec3(passed) + (1.f - passed) * blocked;
        }
        const glm::vec3 h = glm::normalize(toLight - d);
        const float nDotH = std::max(glm::dot(ns, h), 0.f);
        const float specular = m.specular > 0.f ? m.specular * std::pow(nDotH, m.shininess) : 0.f;
        local += transmittance * light.intensity * (m.diffuse * nDotL + glm::vec3(specular)) /
                 attenuation;
    }

    const int maxDepth = std::min(shading.maxDepth, kDepthCeiling);
    float reflectWeight = shading.reflections ? m.reflectivity : 0.f;
    float refractWeight = shading.refractions ? m.transparency : 0.f;
    glm::vec3 color = local * (1.f - std::clamp(m.transparency, 0.f, 1.f));
    if (depth >= maxDepth || (reflectWeight <= 0.f && refractWeight <= 0.f)) return color;

    const float cosI = -glm::dot(ns, d);
    glm::vec3 refracted(0.f);
    if (refractWeight > 0.f) {
        const float eta = entering ? 1.f / m.ior : m.ior; // n_from / n_to
        const float k = 1.f - eta * eta * (1.f - cosI * cosI);
        if (k < 0.f) {
            // Total internal reflection: everything the surface would transmit is reflected.
            reflectWeight += refractWeight;
            refractWeight = 0.f;
        } else {
            const float cosT = std::sqrt(k);
            const float fresnel = schlickFresnel(entering ? cosI : cosT, m.ior);
            reflectWeight += refractWeight * fresnel;
            refractWeight *= 1.f - fresnel;
            const glm::vec3 t = glm::normalize(eta * d + (eta * cosI - cosT) * ns);
            const Ray refractRay{offsetRayOrigin(si.position, si.positionError, ng, t), t};
            refracted = trace(refractRay, RayType::Refraction, depth + 1, policy, counters);
        }
    }
    if (reflectWeight > 0.f) {
        const glm::vec3 r = d - 2.f * glm::dot(ns, d) * ns;
        const Ray reflectRay{offsetRayOrigin(si.position, si.positionError, ng, r), r};
        color += reflectWeight * trace(reflectRay, RayType::Reflection, depth + 1, policy, counters);
    }
    return color + refractWeight * refracted;
}

} // namespace mvcl
