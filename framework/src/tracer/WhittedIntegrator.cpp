#include <mvcl/tracer/WhittedIntegrator.h>

#include "MaterialEvaluator.h"

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

// Alpha-masked hits a ray skips before it gives up and takes the background (foliage cards).
constexpr int kMaxCutOutHits = 64;

bool isFinite(const glm::vec3 &c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

/// Schlick's approximation of dielectric Fresnel reflectance. cosTheta is the cosine on the
/// side of the lower index (the larger angle), as Schlick requires.
float schlickFresnel(float cosTheta, float ior) {
    if (ior == 1.f) return 0.f; // no interface (glTF BLEND without transmission): nothing reflects
    const float r0 = ((1.f - ior) / (1.f + ior)) * ((1.f - ior) / (1.f + ior));
    const float m = std::clamp(1.f - cosTheta, 0.f, 1.f);
    return r0 + (1.f - r0) * m * m * m * m * m;
}

/// The layer the tracer files a geometry under (it clamps out-of-range layers the same way).
int layerOfGeometry(int layer) { return std::clamp(layer, 0, kMaxLayers - 1); }

void countRay(RayType type, RayCounters &counters) {
    switch (type) {
    case RayType::Primary: ++counters.primary; break;
    case RayType::Shadow: ++counters.shadow; break;
    case RayType::Reflection: ++counters.reflection; break;
    case RayType::Refraction: ++counters.refraction; break;
    }
}

} // namespace

WhittedIntegrator::WhittedIntegrator(const Tracer &tracer)
    : m_tracer(tracer), m_materials(std::make_unique<detail::MaterialEvaluator>(tracer.scene())) {
    const Scene &scene = tracer.scene();
    for (const Material &m : scene.materials) {
        // "> 0" here, "not ≤ 0" per layer below: a NaN transparency never forces the walk.
        if (m.transparency > 0.f || (m.alphaMode == AlphaMode::Blend && m.mayTransmit()))
            m_hasTransparentMaterials = true;
        if (m.mayCutOut()) m_hasCutOutMaterials = true;
    }
    // Per layer, what its geometry's materials may do. "Not ≤ 0" rather than "> 0" mirrors the
    // tests in trace(), so that a NaN weight counts as one that may be needed.
    auto addGeometry = [&](int layer, uint32_t material) {
        const uint32_t bit = layerBit(layerOfGeometry(layer));
        m_layersWithGeometry |= bit;
        // An index past the table is not expected from a loader; assume it may do anything.
        const bool known = material < scene.materials.size();
        if (!known || !(scene.materials[material].reflectivity <= 0.f)) m_layersWithReflectiveMaterial |= bit;
        if (!known || scene.materials[material].mayTransmit()) m_layersWithTransmissiveMaterial |= bit;
        if (!known || scene.materials[material].mayCutOut()) m_layersWithCutOutMaterial |= bit;
    };
    for (const TriangleMesh &mesh : scene.meshes) addGeometry(mesh.layer, mesh.material);
    for (const Sphere &sphere : scene.spheres) addGeometry(sphere.layer, sphere.material);
    for (const Plane &plane : scene.planes) addGeometry(plane.layer, plane.material);
}

WhittedIntegrator::~WhittedIntegrator() = default;

IntegratorPlan WhittedIntegrator::plan(const RayPolicy &policy, StageSelection selection) const {
    const ShadingPolicy &shading = policy.shading;
    IntegratorPlan plan;
    if (!shading.shadows || m_tracer.scene().lights.empty())
        plan.forcedShadows = ShadowStage::Off;
    else
        plan.forcedShadows = m_hasTransparentMaterials || m_hasCutOutMaterials ? ShadowStage::TransparentWalk
                                                                               : ShadowStage::AnyHit;
    plan.shadows = plan.forcedShadows;
    // The opacity stage changes what the image shows, so no stage selection skips it.
    for (int layer = 0; layer < kMaxLayers; ++layer)
        if (!(shading.layerOpacity[size_t(layer)] >= 1.f)) plan.translucentLayers |= layerBit(layer);
    plan.translucentLayers &= m_layersWithGeometry & policy.query(RayType::Primary).layerMask;
    if (selection == StageSelection::ForceAll) return plan; // every stage, every colour map

    if (plan.forcedShadows != ShadowStage::Off) {
        const RayQuery &shadowQuery = policy.query(RayType::Shadow);
        // Clip volumes and the t-range only remove hits, so without geometry in the mask no
        // shadow ray can hit anything whatever they say. The integrator only lowers tMax, so a
        // range that is empty in the policy is empty for every light (and the tracer misses).
        const uint32_t casters = m_layersWithGeometry & shadowQuery.layerMask;
        if (casters == 0 || shadowQuery.tMin > shadowQuery.tMax)
            plan.shadows = ShadowStage::Unoccluded;
        else if ((casters & (m_layersWithTransmissiveMaterial | m_layersWithCutOutMaterial)) == 0)
            // Every possible occluder is opaque: the walk would stop at its first hit with 0,
            // which is exactly the any-hit answer.
            plan.shadows = ShadowStage::AnyHit;
    }

    // The secondary stage runs at a hit only below the depth limit and where the material's
    // reflection or refraction weight under the policy is not ≤ 0 (a transmissive material also
    // reflects its Fresnel share, so it counts even with reflections off).
    const uint32_t mayReflectOrRefract = (shading.reflections ? m_layersWithReflectiveMaterial : 0u) |
                                         (shading.refractions ? m_layersWithTransmissiveMaterial : 0u);
    plan.secondaryRayTypes = 0;
    if (std::min(shading.maxDepth, kDepthCeiling) > 0)
        for (const RayType type : {RayType::Primary, RayType::Reflection, RayType::Refraction})
            if ((policy.query(type).layerMask & mayReflectOrRefract) != 0) plan.secondaryRayTypes |= rayTypeBit(type);

    plan.appliesColorMap = !policy.color.isIdentity();
    return plan;
}

float WhittedIntegrator::lightPassing(const Ray &shadowRay, float lightDistance,
                                      const RayPolicy &policy, ShadowStage stage, RayCounters &counters) const {
    RayQuery query = policy.query(RayType::Shadow);
    query.tMax = std::min(query.tMax, lightDistance);
    countRay(RayType::Shadow, counters);
    // Opaque occluders need only "is anything in the way" (any-hit, the cheap query).
    if (stage != ShadowStage::TransparentWalk) return m_tracer.anyHit(shadowRay, query) ? 0.f : 1.f;

    // Transparent occluders let their transparency through (Whitted's transparent shadows):
    // walk the hits along the same ray, each step starting just past the previous hit.
    constexpr int kMaxOccluders = 16;
    float passed = 1.f;
    for (int i = 0; i < kMaxOccluders; ++i) {
        Hit hit;
        if (!m_tracer.closestHit(shadowRay, query, hit)) return passed;
        passed *= m_materials->transmittance(hit);
        if (passed <= 0.f) return 0.f;
        query.tMin = nextFloatUp(hit.t);
        if (query.tMin > query.tMax) return passed;
    }
    return 0.f; // more occluders than we follow: treat the light as blocked
}

glm::vec3 WhittedIntegrator::radiance(const Ray &primaryRay, const RayPolicy &policy,
                                      RayCounters &counters) const {
    return radiance(primaryRay, policy, plan(policy, StageSelection::SkipUnneeded), counters);
}

glm::vec3 WhittedIntegrator::radiance(const Ray &primaryRay, const RayPolicy &policy, const IntegratorPlan &plan,
                                      RayCounters &counters) const {
    return finishSample(trace(primaryRay, RayType::Primary, 0, policy, plan, counters), policy, plan, counters);
}

glm::vec3 WhittedIntegrator::radianceFromHit(const Ray &primaryRay, const Hit *primaryHit, const RayPolicy &policy,
                                             const IntegratorPlan &plan, RayCounters &counters) const {
    countRay(RayType::Primary, counters);
    return finishSample(traceFromHit(primaryRay, RayType::Primary, 0, primaryHit, policy, plan, counters), policy,
                        plan, counters);
}

glm::vec3 WhittedIntegrator::finishSample(glm::vec3 c, const RayPolicy &policy, const IntegratorPlan &plan,
                                          RayCounters &counters) const {
    // The identity map can only turn −0 into +0, and a pixel's sum of samples starts at +0.
    if (plan.appliesColorMap)
        c = policy.color.matrix * c + policy.color.offset;
    else
        ++counters.skippedColorMaps;
    // A non-finite sample would poison the whole pixel: it is counted (tests assert the count
    // stays 0) and replaced by black.
    if (isFinite(c)) return c;
    ++counters.nonFiniteSamples;
    return glm::vec3(0.f);
}

bool WhittedIntegrator::closestVisibleHit(const Ray &ray, const RayQuery &query, Hit &hit) const {
    return m_tracer.closestHit(ray, query, hit) && skipCutOutHits(ray, query, hit);
}

bool WhittedIntegrator::skipCutOutHits(const Ray &ray, const RayQuery &query, Hit &hit) const {
    if (!m_hasCutOutMaterials || !m_materials->isCutOut(hit)) return true;
    // A masked-out hit is not there: look again just past it.
    RayQuery next = query;
    for (int i = 0; i < kMaxCutOutHits; ++i) {
        next.tMin = nextFloatUp(hit.t);
        if (next.tMin > next.tMax || !m_tracer.closestHit(ray, next, hit)) return false;
        if (!m_materials->isCutOut(hit)) return true;
    }
    return false;
}

glm::vec3 WhittedIntegrator::trace(const Ray &ray, RayType type, int depth, const RayPolicy &policy,
                                   const IntegratorPlan &plan, RayCounters &counters) const {
    countRay(type, counters);
    Hit hit;
    const bool found = m_tracer.closestHit(ray, policy.query(type), hit);
    return traceFromHit(ray, type, depth, found ? &hit : nullptr, policy, plan, counters);
}

glm::vec3 WhittedIntegrator::traceFromHit(const Ray &ray, RayType type, int depth, const Hit *closest,
                                          const RayPolicy &policy, const IntegratorPlan &plan,
                                          RayCounters &counters) const {
    const Scene &scene = m_tracer.scene();
    if (!closest) return scene.background;
    Hit hit = *closest;
    if (!skipCutOutHits(ray, policy.query(type), hit)) return scene.background;

    const SurfaceInteraction si = m_tracer.interaction(ray, hit);
    const glm::vec3 d = glm::normalize(ray.direction);
    // The ray cone's width where it meets the surface picks the texture level.
    const float coneWidth = ray.coneWidth + ray.coneSpread * hit.t * glm::length(ray.direction);
    const detail::ShadedSurface surface = m_materials->evaluate(hit, si, d, coneWidth);
    const PhongTerms &m = surface.phong;

    // Light the side the ray arrived on; remember whether it is entering the surface.
    const bool entering = glm::dot(si.geometricNormal, d) < 0.f;
    const glm::vec3 ng = entering ? si.geometricNormal : -si.geometricNormal;
    glm::vec3 ns = entering ? surface.shadingNormal : -surface.shadingNormal;
    if (glm::dot(ns, ng) < 0.f) ns = ng;

    // Eq. 1: A + Σ I·(P·(L·N) + Ks·S·(N·H)^Ps) / D
    const ShadingPolicy &shading = policy.shading;
    // Opacity stage: a partly opaque primary hit is blended with what the ray meets when it goes
    // on through the surface (the same constraints, t still counted from the camera).
    // A primary ray's depth counts the surfaces it went through: depth peeling passes the first
    // peelSurfaces ones at opacity 0.
    float alpha = 1.f;
    glm::vec3 behind(0.f);
    const bool peeled = type == RayType::Primary && depth < std::min(shading.peelSurfaces, kDepthCeiling);
    if (peeled ||
        (type == RayType::Primary && (plan.translucentLayers & layerBit(hit.layer)) != 0 && depth < kDepthCeiling)) {
        const float facing = std::min(std::abs(glm::dot(surface.shadingNormal, d)), 1.f);
        const float opacity = std::clamp(shading.layerOpacity[hit.layer], 0.f, 1.f);
        alpha = peeled ? 0.f : opacity + (1.f - opacity) * std::clamp(shading.edgeOpacity, 0.f, 1.f) * (1.f - facing);
        RayPolicy onwardPolicy = policy;
        RayQuery &onwardQuery = onwardPolicy.query(RayType::Primary);
        onwardQuery.tMin = std::max(0.f, onwardQuery.tMin - hit.t);
        onwardQuery.tMax = onwardQuery.tMax - hit.t;
        Ray onward{offsetRayOrigin(si.position, si.positionError, ng, d), d};
        onward.coneWidth = coneWidth;
        onward.coneSpread = ray.coneSpread;
        // depth + 1 bounds the walk through stacked surfaces (the ceiling); it is no bounce.
        behind = trace(onward, RayType::Primary, depth + 1, onwardPolicy, plan, counters);
        if (alpha <= 0.f) return behind;
    }
    const auto withBehind = [&](const glm::vec3 &front) {
        return alpha < 1.f ? alpha * front + (1.f - alpha) * behind : front;
    };
    glm::vec3 local = m.ambient * scene.ambientLight;
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
        if (plan.shadows != ShadowStage::Off) {
            float passed = 1.f; // what a shadow ray that hits nothing answers
            if (plan.shadows == ShadowStage::Unoccluded) {
                ++counters.skippedShadowRays;
            } else {
                const Ray shadowRay{offsetRayOrigin(si.position, si.positionError, ng, toLight), toLight};
                passed = lightPassing(shadowRay, distance, policy, plan.shadows, counters);
                if (plan.shadows != plan.forcedShadows) ++counters.skippedTransparentWalks;
            }
            // The blocked share of the light is dimmed by the policy's strength and tint.
            const glm::vec3 blocked = glm::mix(glm::vec3(1.f), shading.shadowTint, shading.shadowStrength);
            transmittance = glm::vec3(passed) + (1.f - passed) * blocked;
        }
        const glm::vec3 h = glm::normalize(toLight - d);
        const float nDotH = std::max(glm::dot(ns, h), 0.f);
        const float specular = m.specular > 0.f ? m.specular * std::pow(nDotH, m.shininess) : 0.f;
        local += transmittance * light.intensity * (m.diffuse * nDotL + specular * m.specularColor) /
                 attenuation;
    }

    const int maxDepth = std::min(shading.maxDepth, kDepthCeiling);
    const float reflectivity = shading.reflections ? m.reflectivity : 0.f;
    float reflectWeight = reflectivity;
    float refractWeight = shading.refractions ? surface.transparency : 0.f;
    glm::vec3 color = local * (1.f - std::clamp(surface.transparency, 0.f, 1.f)) + surface.emission;
    if ((plan.secondaryRayTypes & rayTypeBit(type)) == 0) {
        ++counters.skippedSecondaryChecks;
        return withBehind(color);
    }
    if (depth >= maxDepth || (reflectWeight <= 0.f && refractWeight <= 0.f)) return withBehind(color);

    const float cosI = -glm::dot(ns, d);
    glm::vec3 refracted(0.f);
    if (refractWeight > 0.f) {
        const float eta = entering ? 1.f / surface.ior : surface.ior; // n_from / n_to
        const float k = 1.f - eta * eta * (1.f - cosI * cosI);
        if (k < 0.f) {
            // Total internal reflection: everything the surface would transmit is reflected.
            reflectWeight += refractWeight;
            refractWeight = 0.f;
        } else {
            const float cosT = std::sqrt(k);
            const float fresnel = schlickFresnel(entering ? cosI : cosT, surface.ior);
            reflectWeight += refractWeight * fresnel;
            refractWeight *= 1.f - fresnel;
            const glm::vec3 t = glm::normalize(eta * d + (eta * cosI - cosT) * ns);
            Ray refractRay{offsetRayOrigin(si.position, si.positionError, ng, t), t};
            refractRay.coneWidth = coneWidth;
            refractRay.coneSpread = ray.coneSpread;
            refracted = trace(refractRay, RayType::Refraction, depth + 1, policy, plan, counters);
        }
    }
    if (reflectWeight > 0.f) {
        const glm::vec3 r = d - 2.f * glm::dot(ns, d) * ns;
        Ray reflectRay{offsetRayOrigin(si.position, si.positionError, ng, r), r};
        reflectRay.coneWidth = coneWidth;
        reflectRay.coneSpread = ray.coneSpread;
        // Metals tint what they mirror; the Fresnel share of a transmissive surface stays white.
        const glm::vec3 tint = glm::mix(glm::vec3(1.f), m.specularColor,
                                        reflectWeight > 0.f ? std::clamp(reflectivity / reflectWeight, 0.f, 1.f) : 0.f);
        color += reflectWeight * tint * trace(reflectRay, RayType::Reflection, depth + 1, policy, plan, counters);
    }
    return withBehind(color + refractWeight * refracted);
}

} // namespace mvcl
