#include <mvcl/tracer/WhittedIntegrator.h>

#include "ClipCap.h"
#include "MaterialEvaluator.h"
#include "SurfaceOverlays.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/RayOffset.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

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

/// Whether `hit` is on a closed solid (a sphere, or a mesh that is not MeshClosure::Open) and,
/// if so, whether the ray meets it from inside (from its material's side).
enum class SolidSide : uint8_t { NotASolid, Entering, Leaving };
SolidSide solidSide(const Scene &scene, const Hit &hit, const SurfaceInteraction &si, const glm::vec3 &d) {
    const bool facesAway = glm::dot(si.geometricNormal, d) > 0.f;
    bool outward = true;
    switch (hit.kind) {
    case GeometryKind::Sphere: break;
    case GeometryKind::Plane: return SolidSide::NotASolid;
    case GeometryKind::Triangle:
        if (scene.meshes[hit.geometry].closure == MeshClosure::Open) return SolidSide::NotASolid;
        outward = scene.meshes[hit.geometry].closure == MeshClosure::Outward;
        break;
    }
    return facesAway == outward ? SolidSide::Leaving : SolidSide::Entering;
}

/// One key per solid: meshes of one glTF node and mesh bound one solid together (MeshClosure).
uint64_t solidKey(const Scene &scene, const Hit &hit) {
    if (hit.kind == GeometryKind::Triangle) {
        const TriangleMesh &mesh = scene.meshes[hit.geometry];
        if (mesh.sourceNode >= 0) return uint64_t(1) << 63 | uint64_t(uint32_t(mesh.sourceNode)) << 31 | uint32_t(mesh.sourceMesh);
    }
    return uint64_t(hit.kind) << 32 | hit.geometry;
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
    const Bounds3f bounds = scene.bounds();
    if (!bounds.isEmpty()) m_hatchPeriod = glm::length(bounds.extent()) / 160.f;

    std::map<uint64_t, SolidBounds> solids;
    for (uint32_t i = 0; i < scene.meshes.size(); ++i) {
        const TriangleMesh &mesh = scene.meshes[i];
        if (mesh.closure == MeshClosure::Open) continue;
        Hit probe;
        probe.kind = GeometryKind::Triangle;
        probe.geometry = i;
        SolidBounds &solid = solids[solidKey(scene, probe)];
        for (const glm::vec3 &p : mesh.positions) solid.bounds.expand(p);
        solid.layers |= layerBit(layerOfGeometry(mesh.layer));
    }
    for (const auto &[key, solid] : solids) m_solidBounds.push_back(solid);
    for (const Sphere &sphere : scene.spheres)
        m_solidBounds.push_back({{sphere.center - glm::vec3(std::abs(sphere.radius)), sphere.center + glm::vec3(std::abs(sphere.radius))},
                                 layerBit(layerOfGeometry(sphere.layer))});
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

float WhittedIntegrator::lightPassing(const Ray &shadowRay, float lightDistance, const RayQuery &shadowQuery,
                                      ShadowStage stage, RayCounters &counters) const {
    RayQuery query = shadowQuery;
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

bool WhittedIntegrator::solidAround(const Ray &ray, const RayQuery &query, float t, const Hit *firstSurface,
                                    Hit &solid) const {
    // Walk the surfaces beyond t (the query's layers, no clip volumes): the first surface left
    // from inside that was not entered on the way belongs to the innermost solid around t.
    constexpr int kMaxWalk = 16;
    const Scene &scene = m_tracer.scene();
    const glm::vec3 d = glm::normalize(ray.direction);
    RayQuery walk = query;
    walk.clearClips();
    walk.tMin = std::max(walk.tMin, t);
    // Only solids whose (slightly widened) bounds hold the point can hold it, and the ray leaves
    // such a solid before it leaves its bounds: the walk ends there.
    const glm::vec3 point = ray.at(t);
    float leaveBounds = -std::numeric_limits<float>::infinity();
    for (const SolidBounds &candidate : m_solidBounds) {
        if ((candidate.layers & query.layerMask) == 0) continue;
        const glm::vec3 margin = 1e-4f * candidate.bounds.extent() + 1e-6f * glm::abs(point);
        const glm::vec3 lo = candidate.bounds.min - margin, hi = candidate.bounds.max + margin;
        if (!glm::all(glm::greaterThanEqual(point, lo)) || !glm::all(glm::lessThanEqual(point, hi))) continue;
        float leave = std::numeric_limits<float>::infinity();
        for (int axis = 0; axis < 3; ++axis)
            if (ray.direction[axis] != 0.f)
                leave = std::min(leave, ((ray.direction[axis] > 0.f ? hi[axis] : lo[axis]) - ray.origin[axis]) /
                                            ray.direction[axis]);
        leaveBounds = std::max(leaveBounds, leave);
    }
    if (!(leaveBounds >= walk.tMin)) return false;
    walk.tMax = std::min(walk.tMax, nextFloatUp(leaveBounds));
    std::array<uint64_t, kMaxWalk> entered{};
    int enteredCount = 0;
    for (int step = 0; step < kMaxWalk && walk.tMin <= walk.tMax; ++step) {
        Hit hit;
        if (step == 0 && firstSurface)
            hit = *firstSurface;
        else if (!closestVisibleHit(ray, walk, hit))
            return false;
        if (hit.t > walk.tMax) return false;
        const SolidSide side = solidSide(scene, hit, m_tracer.interaction(ray, hit), d);
        const uint64_t key = solidKey(scene, hit);
        if (side == SolidSide::Entering) {
            entered[size_t(enteredCount++)] = key;
        } else if (side == SolidSide::Leaving) {
            const auto end = entered.begin() + enteredCount;
            const auto it = std::find(entered.begin(), end, key);
            if (it == end) {
                solid = hit;
                return true;
            }
            std::copy(it + 1, end, it); // left a solid entered after t
            --enteredCount;
        }
        walk.tMin = nextFloatUp(hit.t);
    }
    return false; // more surfaces than we follow: no cap
}

glm::vec3 WhittedIntegrator::trace(const Ray &ray, RayType type, int depth, const RayPolicy &policy,
                                   const IntegratorPlan &plan, RayCounters &counters, float travelled) const {
    countRay(type, counters);
    Hit hit;
    const bool found = m_tracer.closestHit(ray, policy.query(type), hit);
    return traceFromHit(ray, type, depth, found ? &hit : nullptr, policy, plan, counters, travelled);
}

glm::vec3 WhittedIntegrator::traceFromHit(const Ray &ray, RayType type, int depth, const Hit *closest,
                                          const RayPolicy &policy, const IntegratorPlan &plan, RayCounters &counters,
                                          float travelled) const {
    const Scene &scene = m_tracer.scene();
    const ShadingPolicy &shading = policy.shading;
    const RayQuery &query = policy.query(type);
    const bool isPrimary = type == RayType::Primary;
    const glm::vec3 d = glm::normalize(ray.direction);
    const float rayLength = glm::length(ray.direction);
    // Where a primary ray crosses a capped clip surface into a closed solid, it shows the cut
    // face there, as a solid face of that solid's material, in front of whatever lies inside.
    std::optional<detail::ClipCap> cap;
    Hit hit = closest ? *closest : Hit{};
    const bool found = closest && skipCutOutHits(ray, query, hit);
    if (!found) hit = Hit{};
    SurfaceInteraction si;
    if (isPrimary && detail::hasCappedClip(query)) {
        // The run of accepted points that holds the hit, or (no hit at all: a slab through a
        // solid) the first run, begins on a capped surface: is that point inside a solid?
        cap = found ? detail::clipCapBefore(ray, query, hit.t) : detail::firstCappedRunStart(ray, query);
        Hit solid;
        // Between the run's start and the accepted hit every point is accepted, so that hit is
        // the first surface beyond the start: the walk begins with it.
        if (cap && solidAround(ray, query, cap->t, found ? &hit : nullptr, solid))
            hit = solid;
        else
            cap.reset();
    }
    if (found || cap) si = m_tracer.interaction(ray, hit);
    if (!found && !cap) {
        // An outline is centred on the silhouette, so the background next to it gets half.
        if (!isPrimary || shading.edges.mode != EdgeLineMode::Outlines) return scene.background;
        return glm::mix(scene.background, shading.edges.color,
                        outlineCoverage(ray, query, nullptr, shading.edges, counters));
    }
    const float shownT = cap ? cap->t : hit.t;
    // The ray cone's width where it meets the surface picks the texture level.
    const float coneWidth = ray.coneWidth + ray.coneSpread * shownT * rayLength;
    detail::ShadedSurface surface = m_materials->evaluate(hit, si, d, coneWidth);
    if (cap) {
        si.position = ray.at(cap->t);
        // ray.at() rounds once per component; a few ulps of the largest term bound the error.
        si.positionError = 8.f * std::numeric_limits<float>::epsilon() *
                           (glm::abs(ray.origin) + glm::abs(cap->t * ray.direction));
        si.geometricNormal = surface.shadingNormal = cap->normal;
        // A section is matte and opaque: a metal shows its colour rather than a mirror, glass
        // looks frosted (what it would transmit scatters).
        PhongTerms &section = surface.phong;
        const float clear = std::clamp(surface.transparency, 0.f, 1.f);
        section.diffuse = glm::mix(section.diffuse + section.reflectivity * section.specularColor, glm::vec3(0.8f), clear);
        section.ambient = glm::mix(section.ambient, glm::vec3(0.8f), clear);
        surface.transparency = 0.f;
    }
    const PhongTerms &m = surface.phong;

    // Light the side the ray arrived on; remember whether it is entering the surface.
    const bool entering = glm::dot(si.geometricNormal, d) < 0.f;
    const glm::vec3 ng = entering ? si.geometricNormal : -si.geometricNormal;
    glm::vec3 ns = entering ? surface.shadingNormal : -surface.shadingNormal;
    if (glm::dot(ns, ng) < 0.f) ns = ng;

    // Opacity stage: a partly opaque primary hit is blended with what the ray meets when it goes
    // on through the surface (the same constraints, t still counted from the camera).
    // A primary ray's depth counts the surfaces it went through: depth peeling passes the first
    // peelSurfaces ones at opacity 0. A cap is solid: nothing shows through it.
    float alpha = 1.f;
    glm::vec3 behind(0.f);
    const bool peeled = isPrimary && !cap && depth < std::min(shading.peelSurfaces, kDepthCeiling);
    if (peeled ||
        (isPrimary && !cap && (plan.translucentLayers & layerBit(hit.layer)) != 0 && depth < kDepthCeiling)) {
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
        behind = trace(onward, RayType::Primary, depth + 1, onwardPolicy, plan, counters,
                       travelled + hit.t * rayLength);
        if (alpha <= 0.f) return behind;
    }
    // Lines go over the surface's colour, which then blends with what lies behind it.
    const auto shown = [&](const glm::vec3 &surfaceColor) {
        glm::vec3 front = surfaceColor;
        // A cap is no surface of the mesh its hit lies on: it gets no lines of its own.
        if (isPrimary && !cap && shading.edges.mode != EdgeLineMode::Off) {
            float lines = 0.f;
            if (shading.edges.mode == EdgeLineMode::Outlines)
                lines = outlineCoverage(ray, query, &hit, shading.edges, counters);
            else if (hit.kind == GeometryKind::Triangle)
                lines = detail::triangleEdgeCoverage(scene.meshes[hit.geometry], hit, coneWidth,
                                                     shading.edges.widthPixels);
            front = glm::mix(front, shading.edges.color, lines);
        }
        return alpha < 1.f ? alpha * front + (1.f - alpha) * behind : front;
    };
    if (isPrimary && shading.falseColor.mode != FalseColorMode::Off)
        return shown(detail::falseColorAt(shading.falseColor, hit, ns, travelled + shownT * rayLength,
                                          std::min(std::abs(glm::dot(ns, d)), 1.f)));

    // A cap is lit as if the cut were real: its shadow rays skip what the primary clips remove.
    RayQuery shadowQuery = policy.query(RayType::Shadow);
    if (cap)
        for (const ClipVolume &clip : query.clips()) shadowQuery.tryAddClip(clip);

    // Eq. 1: A + Σ I·(P·(L·N) + Ks·S·(N·H)^Ps) / D
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
                passed = lightPassing(shadowRay, distance, shadowQuery, plan.shadows, counters);
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
    if (cap) return shown(cap->style == ClipVolume::CapStyle::Hatched ? detail::hatched(color, si.position, m_hatchPeriod)
                                                                       : color);
    if ((plan.secondaryRayTypes & rayTypeBit(type)) == 0) {
        ++counters.skippedSecondaryChecks;
        return shown(color);
    }
    if (depth >= maxDepth || (reflectWeight <= 0.f && refractWeight <= 0.f)) return shown(color);

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
    return shown(color + refractWeight * refracted);
}

} // namespace mvcl
