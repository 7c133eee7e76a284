#include <mvcl/tracer/WhittedIntegrator.h>

#include "ClipCap.h"
#include "Lanes3.h"
#include "MaterialEvaluator.h"
#include "SurfaceOverlays.h"

#include <mvcl/core/Error.h>
#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/RayOffset.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <string>

namespace mvcl {

namespace {

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

void countRay(RayType type, RayCounters &counters) {
    switch (type) {
    case RayType::Primary: ++counters.primary; break;
    case RayType::Shadow: ++counters.shadow; break;
    case RayType::Reflection: ++counters.reflection; break;
    case RayType::Refraction: ++counters.refraction; break;
    }
}

} // namespace

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

bool WhittedIntegrator::plainMissRadiance(const RayPolicy &policy, const IntegratorPlan &plan, glm::vec3 &radiance,
                                          RayCounters &counters) const {
    if (policy.shading.edges.mode == EdgeLineMode::Outlines || detail::hasCappedClip(policy.query(RayType::Primary)))
        return false;
    radiance = finishSample(m_scene.background, policy, plan, counters);
    return true;
}

glm::vec3 WhittedIntegrator::trace(const Ray &ray, RayType type, int depth, const RayPolicy &policy,
                                   const IntegratorPlan &plan, RayCounters &counters, float travelled) const {
    countRay(type, counters);
    Hit hit;
    const bool found = m_tracer.closestHit(ray, policy.query(type), hit);
    return traceFromHit(ray, type, depth, found ? &hit : nullptr, policy, plan, counters, travelled);
}

/// What traceFromHit() knows of the surface point a ray shows before its light loop: the hit (or
/// the cap in front of it), the lit side's normals, the material's terms, and what lies behind a
/// translucent primary hit. Made by prepareShading(), lit by litColor().
struct WhittedIntegrator::ShadingPoint {
    /// Leaves every member but `cap` to prepareShading(), which writes each one before it is
    /// read: the members' own zeroing, a few hundred bytes a ray, showed in the profile.
    ShadingPoint() {}

    union { Ray ray; };
    union { Hit hit; };
    union { SurfaceInteraction si; };
    union { detail::ShadedSurface surface; };
    std::optional<detail::ClipCap> cap;
    RayType type;
    int depth;
    float travelled;
    glm::vec3 d;       ///< unit direction of the ray
    float rayLength;   ///< |ray.direction|
    float coneWidth;   ///< the ray cone's width at the surface
    float shownT;      ///< t of the point shown (the cap's, or the hit's)
    bool entering;     ///< the ray meets the surface from the side its normal faces
    glm::vec3 ng, ns;  ///< geometric and shading normals on the lit side
    float alpha;       ///< opacity stage: the surface's share, blended over `behind`
    glm::vec3 behind;
    /// originOffsetAlong(si.positionError, ng): the one error projection every ray the point
    /// spawns is offset by (each offsetRayOrigin() call found it again). Found with the normals:
    /// found lazily, by the first ray that needs it, it cost more than it saved.
    glm::vec3 originOffset;
    /// The spawn origin on ng's side, found by the first ray that leaves there: every shadow ray
    /// (lightPath() only answers lights on that side) and most reflected rays start from it.
    mutable bool hasOriginAbove;
    mutable glm::vec3 originAbove;

    /// offsetRayOrigin(si.position, si.positionError, ng, w), bit for bit.
    glm::vec3 spawnOrigin(const glm::vec3 &w) const {
        if (leavesBehind(ng, w)) return offsetPoint(si.position, -originOffset);
        if (!hasOriginAbove) {
            originAbove = offsetPoint(si.position, originOffset);
            hasOriginAbove = true;
        }
        return originAbove;
    }
};

namespace {

/// How a light reaches a surface point: unit direction toward it, distance (∞ for directional
/// lights), attenuation and the cosine at the shading normal.
/// Left uninitialised: lightPath() writes every member it answers true for, and a batch's
/// answers (16 points × 8 lights) were zeroed at every step before.
struct LightPath {
    glm::vec3 toLight;
    float distance;
    float attenuation;
    float nDotL;
};

/// The path from the point at `position` (lit side normals ng, ns) to `light`; false where the
/// light adds nothing (behind the surface, on it, or attenuated away). Always inlined, as is
/// directLight(): as calls, their set-up and saved registers were about a tenth of a point's
/// direct light.
[[gnu::always_inline]] inline bool lightPath(const glm::vec3 &position, const glm::vec3 &ng, const glm::vec3 &ns,
                                             const Light &light, LightPath &path) {
    if (light.type == LightType::Directional) {
        path.toLight = -light.direction;
        path.distance = std::numeric_limits<float>::infinity();
        path.attenuation = 1.f;
    } else {
        path.toLight = light.position - position;
        path.distance = glm::length(path.toLight);
        if (!(path.distance > 0.f)) return false; // light exactly on the surface
        path.toLight /= path.distance;
        path.attenuation = light.constantAttenuation + light.linearAttenuation * path.distance +
                           light.quadraticAttenuation * path.distance * path.distance;
        if (!(path.attenuation > 0.f)) return false;
    }
    path.nDotL = glm::dot(ns, path.toLight);
    return path.nDotL > 0.f && glm::dot(ng, path.toLight) > 0.f;
}

/// Lights whose shadow rays radianceFromHits() traces as packets; any further light of a scene
/// is traced ray by ray (scenes rarely have more).
constexpr std::size_t kPacketLights = 8;

} // namespace

/// What radianceFromHits() found for one point and one light: its path (found once, used by the
/// packet and then by the shading) and what the shadow ray answered.
struct WhittedIntegrator::LightAnswer {
    bool lit;     ///< lightPath() holds: the light reaches the point's lit side
    LightPath path;
    float passed; ///< lightPassing()'s answer, set where `lit`
};

// Inlined into traceFromHit() and radianceFromHits(): as calls, the split of the shading into
// two halves cost the ray-by-ray path (every secondary ray) several per cent.
[[gnu::always_inline]] inline bool
WhittedIntegrator::prepareShading(const Ray &ray, RayType type, int depth, const Hit *closest, const RayPolicy &policy,
                                  const IntegratorPlan &plan, RayCounters &counters, float travelled, ShadingPoint &p,
                                  glm::vec3 &finished) const {
    const Scene &scene = m_scene;
    const ShadingPolicy &shading = policy.shading;
    const RayQuery &query = policy.query(type);
    const bool isPrimary = type == RayType::Primary;
    // A miss shows the background (or, under outlines, the background next to an edge) unless a
    // capped clip puts a cap on its way: most rays of a model's frame end here, before any of the
    // point's set-up.
    const bool mayCap = isPrimary && detail::hasCappedClip(query);
    if (!closest && !mayCap) {
        finished = !isPrimary || shading.edges.mode != EdgeLineMode::Outlines
                       ? scene.background
                       : glm::mix(scene.background, shading.edges.color,
                                  outlineCoverage(ray, query, nullptr, shading.edges, counters));
        return false;
    }
    p.ray = ray;
    p.type = type;
    p.depth = depth;
    p.travelled = travelled;
    // glm::length and glm::normalize (d · (1 / sqrt(d·d))) from one square root.
    p.rayLength = glm::length(ray.direction);
    p.d = ray.direction * (1.f / p.rayLength);
    // Where a primary ray crosses a capped clip surface into a closed solid, it shows the cut
    // face there, as a solid face of that solid's material, in front of whatever lies inside.
    std::optional<detail::ClipCap> &cap = p.cap;
    // Each union member of the point starts its life as p.member = ..., or, for the results of
    // interaction() and evaluate(), constructed in place by a placement new (an assignment
    // returned them into a temporary and copied it, some hundred bytes a point).
    p.hit = closest ? *closest : Hit{};
    Hit &hit = p.hit;
    // The scene test first: the call costs a shaded point more than the test (no mask: no call).
    const bool found = closest && (!m_hasCutOutMaterials || skipCutOutHits(ray, query, hit));
    if (!found) hit = Hit{};
    SurfaceInteraction &si = p.si;
    if (mayCap) {
        // The run of accepted points that holds the hit, or (no hit at all: a slab through a
        // solid) the first run, begins on a capped surface: is that point inside a solid?
        cap = found ? detail::nearestClipCap(ray, query, hit.t, hit.layer) : detail::firstCappedRunStart(ray, query);
        Hit solid;
        // Between the run's start and the accepted hit every point is accepted, so that hit is
        // the first surface beyond the start: the walk begins with it. Only a solid of a layer
        // the capping volume cuts gets the cap.
        if (cap && solidAround(ray, query, cap->t, found ? &hit : nullptr, solid) &&
            ((cap->layers >> solid.layer) & 1u))
            hit = solid;
        else
            cap.reset();
    }
    if (found || cap) ::new (&p.si) SurfaceInteraction(m_tracer.interaction(ray, hit));
    if (!found && !cap) {
        // An outline is centred on the silhouette, so the background next to it gets half.
        if (!isPrimary || shading.edges.mode != EdgeLineMode::Outlines)
            finished = scene.background;
        else
            finished = glm::mix(scene.background, shading.edges.color,
                                outlineCoverage(ray, query, nullptr, shading.edges, counters));
        return false;
    }
    p.shownT = cap ? cap->t : hit.t;
    // The ray cone's width where it meets the surface picks the texture level.
    p.coneWidth = ray.coneWidth + ray.coneSpread * p.shownT * p.rayLength;
    ::new (&p.surface) detail::ShadedSurface(m_materials->evaluate(hit, si, p.d, p.coneWidth));
    detail::ShadedSurface &surface = p.surface;
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

    // Light the side the ray arrived on; remember whether it is entering the surface.
    const glm::vec3 &d = p.d;
    p.entering = glm::dot(si.geometricNormal, d) < 0.f;
    p.ng = p.entering ? si.geometricNormal : -si.geometricNormal;
    p.ns = p.entering ? surface.shadingNormal : -surface.shadingNormal;
    if (glm::dot(p.ns, p.ng) < 0.f) p.ns = p.ng;
    p.originOffset = originOffsetAlong(si.positionError, p.ng);
    p.hasOriginAbove = false;

    // Opacity stage: a partly opaque primary hit is blended with what the ray meets when it goes
    // on through the surface (the same constraints, t still counted from the camera).
    // A primary ray's depth counts the surfaces it went through: depth peeling passes the first
    // peelSurfaces ones at opacity 0. A cap is solid: nothing shows through it.
    p.alpha = 1.f;
    p.behind = glm::vec3(0.f);
    const bool peeled = isPrimary && !cap && depth < std::min(shading.peelSurfaces, kDepthCeiling) &&
                        (shading.peelLayers & layerBit(hit.layer)) != 0;
    if (peeled ||
        (isPrimary && !cap && (plan.translucentLayers & layerBit(hit.layer)) != 0 && depth < kDepthCeiling)) {
        const float facing = std::min(std::abs(glm::dot(surface.shadingNormal, d)), 1.f);
        const float opacity = std::clamp(shading.layerOpacity[hit.layer], 0.f, 1.f);
        p.alpha = peeled ? 0.f : opacity + (1.f - opacity) * std::clamp(shading.edgeOpacity, 0.f, 1.f) * (1.f - facing);
        RayPolicy onwardPolicy = policy;
        RayQuery &onwardQuery = onwardPolicy.query(RayType::Primary);
        onwardQuery.tMin = std::max(0.f, onwardQuery.tMin - hit.t);
        onwardQuery.tMax = onwardQuery.tMax - hit.t;
        Ray onward{p.spawnOrigin(d), d};
        onward.coneWidth = p.coneWidth;
        onward.coneSpread = ray.coneSpread;
        // depth + 1 bounds the walk through stacked surfaces (the ceiling); it is no bounce.
        p.behind = trace(onward, RayType::Primary, depth + 1, onwardPolicy, plan, counters,
                         travelled + hit.t * p.rayLength);
        if (p.alpha <= 0.f) {
            finished = p.behind;
            return false;
        }
    }
    if (isPrimary && shading.falseColor.mode != FalseColorMode::Off) {
        finished = shown(p, detail::falseColorAt(shading.falseColor, hit, p.ns, travelled + p.shownT * p.rayLength,
                                                 std::min(std::abs(glm::dot(p.ns, d)), 1.f)),
                         policy, counters);
        return false;
    }
    return true;
}

glm::vec3 WhittedIntegrator::shown(const ShadingPoint &p, const glm::vec3 &surfaceColor, const RayPolicy &policy,
                                   RayCounters &counters) const {
    // Lines go over the surface's colour, which then blends with what lies behind it.
    const EdgePolicy &edges = policy.shading.edges;
    glm::vec3 front = surfaceColor;
    // A cap is no surface of the mesh its hit lies on: it gets no lines of its own.
    if (p.type == RayType::Primary && !p.cap && edges.mode != EdgeLineMode::Off) {
        float lines = 0.f;
        if (edges.mode == EdgeLineMode::Outlines)
            lines = outlineCoverage(p.ray, policy.query(p.type), &p.hit, edges, counters);
        else if (p.hit.kind == GeometryKind::Triangle)
            lines = detail::triangleEdgeCoverage(m_scene.meshes[p.hit.geometry], p.hit, p.coneWidth,
                                                 edges.widthPixels);
        front = glm::mix(front, edges.color, lines);
    }
    return p.alpha < 1.f ? p.alpha * front + (1.f - p.alpha) * p.behind : front;
}

glm::vec3 WhittedIntegrator::shadowBlockedShare(const ShadingPolicy &shading) {
    // The blocked share of a light is dimmed by the policy's strength and tint.
    return glm::mix(glm::vec3(1.f), shading.shadowTint, shading.shadowStrength);
}

// Inlined into litColor() (see lightPath()).
[[gnu::always_inline]] inline glm::vec3
WhittedIntegrator::directLight(const ShadingPoint &p, const IntegratorPlan &plan, RayCounters &counters,
                               const LightAnswer *answers, const RayQuery &shadowQuery,
                               const glm::vec3 &shadowBlocked) const {
    const Scene &scene = m_scene;
    const PhongTerms &m = p.surface.phong;
    const glm::vec3 &ns = p.ns;
    // Eq. 1: A + Σ I·(P·(L·N) + Ks·S·(N·H)^Ps) / D, the colour arithmetic in SSE lanes (Lanes3:
    // the same operations, the same bits, a third of the instructions of glm's vec3).
    using detail::Lanes3;
    Lanes3 local = Lanes3::of(m.ambient) * Lanes3::of(scene.ambientLight);
    // Pointers, not indices: lights.size() is a division by sizeof(Light) (44), at every step.
    const Light *const lights = scene.lights.data(), *const lightsEnd = lights + scene.lights.size();
    // The lights with an answer: the first kPacketLights, where shadeBatch() traced packets.
    const Light *const answered = answers ? lights + std::min(scene.lights.size(), kPacketLights) : lights;
    for (const Light *lightIt = lights; lightIt != lightsEnd; ++lightIt) {
        const Light &light = *lightIt;
        const LightAnswer *answer = lightIt < answered ? &answers[lightIt - lights] : nullptr;
        LightPath path;
        if (answer) {
            if (!answer->lit) continue;
            path = answer->path;
        } else if (!lightPath(p.si.position, p.ng, ns, light, path)) {
            continue;
        }

        Lanes3 transmittance = Lanes3::splat(1.f);
        if (plan.shadows != ShadowStage::Off) {
            float passed = 1.f; // what a shadow ray that hits nothing answers
            if (plan.shadows == ShadowStage::Unoccluded) {
                ++counters.skippedShadowRays;
            } else {
                countRay(RayType::Shadow, counters);
                passed = answer ? answer->passed
                                : lightPassing(Ray{p.spawnOrigin(path.toLight), path.toLight}, path.distance, shadowQuery,
                                               plan.shadows);
                if (plan.shadows != plan.forcedShadows) ++counters.skippedTransparentWalks;
            }
            transmittance = Lanes3::splat(passed) + Lanes3::splat(1.f - passed) * Lanes3::of(shadowBlocked);
        }
        // glm::normalize(path.toLight - p.d): v · (1 / sqrt(v·v)).
        Lanes3 h = Lanes3::of(path.toLight) - Lanes3::of(p.d);
        h = h * Lanes3::splat(1.f / std::sqrt(dot(h, h)));
        const float nDotH = std::max(dot(Lanes3::of(ns), h), 0.f);
        const float specular = m.specular > 0.f ? m.specular * std::pow(nDotH, m.shininess) : 0.f;
        local = local + transmittance * Lanes3::of(light.intensity) *
                            (Lanes3::of(m.diffuse) * Lanes3::splat(path.nDotL) +
                             Lanes3::splat(specular) * Lanes3::of(m.specularColor)) /
                            Lanes3::splat(path.attenuation);
    }
    return local.toVec3();
}

/// What a lit point still needs from its secondary rays: its own colour, and the reflected and
/// refracted rays with the weights their radiance is added with. Made by litColor().
struct WhittedIntegrator::SecondaryRays {
    glm::vec3 color;         ///< local light · (1 − transparency) + emission
    glm::vec3 reflectFactor; ///< reflection weight · tint, applied to the reflected radiance
    float refractWeight;     ///< applied to the refracted radiance (0 under total internal reflection)
    bool reflects;           ///< reflectRay is traced
    bool refracts;           ///< refractRay is traced
    Ray reflectRay;
    Ray refractRay;
};

[[gnu::always_inline]] inline bool WhittedIntegrator::litColor(const ShadingPoint &p, const RayPolicy &policy,
                                                               const IntegratorPlan &plan, RayCounters &counters,
                                                               const LightAnswer *answers, const glm::vec3 &shadowBlocked,
                                                               SecondaryRays &next, glm::vec3 &finished) const {
    const ShadingPolicy &shading = policy.shading;
    const PhongTerms &m = p.surface.phong;
    const glm::vec3 &d = p.d, &ns = p.ns;
    const SurfaceInteraction &si = p.si;

    glm::vec3 local;
    if (p.cap) {
        // A cap is lit as if the cut were real: its shadow rays skip what the primary clips remove.
        RayQuery cappedShadowQuery = policy.query(RayType::Shadow);
        for (const ClipVolume &clip : policy.query(p.type).clips()) cappedShadowQuery.tryAddClip(clip);
        local = directLight(p, plan, counters, answers, cappedShadowQuery, shadowBlocked);
    } else {
        local = directLight(p, plan, counters, answers, policy.query(RayType::Shadow), shadowBlocked);
    }

    const int maxDepth = std::min(shading.maxDepth, kDepthCeiling);
    const float reflectivity = shading.reflections ? m.reflectivity : 0.f;
    float reflectWeight = reflectivity;
    float refractWeight = shading.refractions ? p.surface.transparency : 0.f;
    const glm::vec3 color = local * (1.f - std::clamp(p.surface.transparency, 0.f, 1.f)) + p.surface.emission;
    if (p.cap) {
        finished = shown(p, p.cap->style == ClipVolume::CapStyle::Hatched ? detail::hatched(color, si.position, m_hatchPeriod)
                                                                          : color,
                         policy, counters);
        return false;
    }
    if ((plan.secondaryRayTypes & rayTypeBit(p.type)) == 0) {
        ++counters.skippedSecondaryChecks;
        finished = shown(p, color, policy, counters);
        return false;
    }
    if (p.depth >= maxDepth || (reflectWeight <= 0.f && refractWeight <= 0.f)) {
        finished = shown(p, color, policy, counters);
        return false;
    }

    next.color = color;
    next.refracts = false;
    const float cosI = -glm::dot(ns, d);
    if (refractWeight > 0.f) {
        const float ior = p.surface.ior;
        const float eta = p.entering ? 1.f / ior : ior; // n_from / n_to
        const float k = 1.f - eta * eta * (1.f - cosI * cosI);
        if (k < 0.f) {
            // Total internal reflection: everything the surface would transmit is reflected.
            reflectWeight += refractWeight;
            refractWeight = 0.f;
        } else {
            const float cosT = std::sqrt(k);
            const float fresnel = schlickFresnel(p.entering ? cosI : cosT, ior);
            reflectWeight += refractWeight * fresnel;
            refractWeight *= 1.f - fresnel;
            const glm::vec3 t = glm::normalize(eta * d + (eta * cosI - cosT) * ns);
            next.refractRay = Ray{p.spawnOrigin(t), t};
            next.refractRay.coneWidth = p.coneWidth;
            next.refractRay.coneSpread = p.ray.coneSpread;
            next.refracts = true;
        }
    }
    next.refractWeight = refractWeight;
    next.reflects = reflectWeight > 0.f;
    if (next.reflects) {
        const glm::vec3 r = d - 2.f * glm::dot(ns, d) * ns;
        next.reflectRay = Ray{p.spawnOrigin(r), r};
        next.reflectRay.coneWidth = p.coneWidth;
        next.reflectRay.coneSpread = p.ray.coneSpread;
        // Metals tint what they mirror; the Fresnel share of a transmissive surface stays white.
        const glm::vec3 tint = glm::mix(glm::vec3(1.f), m.specularColor, std::clamp(reflectivity / reflectWeight, 0.f, 1.f));
        next.reflectFactor = reflectWeight * tint;
    }
    return true;
}

/// The colour of a point from its own colour and its secondary rays' radiance: the recursive
/// traceFromHit() and the stream (radianceFromHits()) add the same terms in the same order
/// through it, so both give the same bits.
inline glm::vec3 combineSecondary(const glm::vec3 &color, const glm::vec3 &reflectFactor, bool reflects,
                                  const glm::vec3 &reflected, float refractWeight, const glm::vec3 &refracted) {
    glm::vec3 sum = color;
    if (reflects) sum += reflectFactor * reflected;
    return sum + refractWeight * refracted;
}

glm::vec3 WhittedIntegrator::traceFromHit(const Ray &ray, RayType type, int depth, const Hit *closest,
                                          const RayPolicy &policy, const IntegratorPlan &plan, RayCounters &counters,
                                          float travelled) const {
    ShadingPoint p;
    glm::vec3 finished;
    if (!prepareShading(ray, type, depth, closest, policy, plan, counters, travelled, p, finished)) return finished;
    SecondaryRays next;
    if (!litColor(p, policy, plan, counters, nullptr, shadowBlockedShare(policy.shading), next, finished))
        return finished;
    const glm::vec3 refracted =
        next.refracts ? trace(next.refractRay, RayType::Refraction, p.depth + 1, policy, plan, counters) : glm::vec3(0.f);
    const glm::vec3 reflected =
        next.reflects ? trace(next.reflectRay, RayType::Reflection, p.depth + 1, policy, plan, counters) : glm::vec3(0.f);
    return shown(p, combineSecondary(next.color, next.reflectFactor, next.reflects, reflected, next.refractWeight, refracted),
                 policy, counters);
}

/// Where a value of the stream goes once known: a primary sample (radiance[i]) or the reflected
/// or refracted slot of a point waiting for its secondary rays.
struct WhittedIntegrator::Destination {
    int node;  ///< index into the waiting points, or −1 for a primary sample
    int index; ///< the primary sample (node = −1), or 0 = reflected, 1 = refracted
};

/// Where a secondary ray of the stream comes from and where its radiance goes (the ray itself
/// waits beside it, in StreamScratch::rays).
struct WhittedIntegrator::StreamRoute {
    int depth;
    Destination to;
    int root; ///< the primary ray whose sample this ray serves (its rays are counted there)
};

/// A point whose colour waits for its secondary rays' radiance (SecondaryRays, and what they
/// brought back).
struct WhittedIntegrator::WaitingPoint {
    glm::vec3 color;
    glm::vec3 reflectFactor;
    float refractWeight;
    bool reflects;
    Destination to;
    int root; ///< as StreamRoute::root
    glm::vec3 secondary[2]; ///< reflected, refracted radiance (0 where not traced)
};

/// The stream's working memory, one per thread, reused block after block.
struct WhittedIntegrator::StreamScratch {
    std::vector<WaitingPoint> waiting;
    /// Reflection, refraction: the next waves' rays, apart from their routes so that a wave is
    /// traced straight from here (no copy into a packet array, whose rays' initialisers ran at
    /// every wave).
    std::vector<Ray> rays[2];
    std::vector<StreamRoute> routes[2];
    /// A wave's closest hits, here for the same reason.
    std::array<Hit, Tracer::kPacketSize> hits;
};

// Not inlined: the address it returns is then an ordinary pointer the caller keeps. Inlined, the
// compiler recomputed the thread_local's address at every use, a __tls_get_addr call (this is a
// shared library) once a ray.
[[gnu::noinline]] WhittedIntegrator::StreamScratch &WhittedIntegrator::threadStreamScratch() {
    thread_local StreamScratch scratch;
    return scratch;
}

void WhittedIntegrator::shadeBatch(std::span<ShadingPoint> points, uint32_t lit, const Destination *to,
                                   const int *root, const RayPolicy &policy, const IntegratorPlan &plan,
                                   std::span<RayCounters> counters, StreamScratch &scratch,
                                   std::span<glm::vec3> radiance) const {
    // Opaque occluders only (any-hit answers): the shadow rays of all points toward one light
    // are one packet, coherent where the points are neighbours. A point on a cap has its own
    // shadow query (the cut's clips added) and goes ray by ray, as do transparent walks.
    uint32_t packeted = 0;
    if (plan.shadows == ShadowStage::AnyHit)
        for (uint32_t rest = lit; rest; rest &= rest - 1)
            if (!points[size_t(std::countr_zero(rest))].cap) packeted |= rest & ~(rest - 1);
    const std::vector<Light> &lights = m_scene.lights;
    std::array<std::array<LightAnswer, kPacketLights>, Tracer::kPacketSize> answers;
    for (std::size_t l = 0; packeted && l < std::min(lights.size(), kPacketLights); ++l) {
        std::array<Ray, Tracer::kPacketSize> rays;
        std::array<float, Tracer::kPacketSize> distances;
        std::array<int, Tracer::kPacketSize> pointOf;
        std::size_t n = 0;
        for (uint32_t rest = packeted; rest; rest &= rest - 1) {
            const int i = std::countr_zero(rest);
            const ShadingPoint &p = points[size_t(i)];
            LightAnswer &a = answers[size_t(i)][l];
            a.lit = lightPath(p.si.position, p.ng, p.ns, lights[l], a.path);
            if (!a.lit) continue;
            rays[n] = Ray{p.spawnOrigin(a.path.toLight), a.path.toLight};
            distances[n] = a.path.distance;
            pointOf[n++] = i;
        }
        if (n == 0) continue;
        const uint32_t occluded =
            m_tracer.anyHits({rays.data(), n}, policy.query(RayType::Shadow), {distances.data(), n});
        for (std::size_t j = 0; j < n; ++j) answers[size_t(pointOf[j])][l].passed = (occluded >> j) & 1u ? 0.f : 1.f;
    }
    const glm::vec3 shadowBlocked = shadowBlockedShare(policy.shading);
    for (uint32_t rest = lit; rest; rest &= rest - 1) {
        const std::size_t i = size_t(std::countr_zero(rest));
        const ShadingPoint &p = points[i];
        SecondaryRays next;
        glm::vec3 finished;
        RayCounters &own = counters[size_t(root[i])];
        if (!litColor(p, policy, plan, own, (packeted >> i) & 1u ? answers[i].data() : nullptr, shadowBlocked, next,
                      finished)) {
            deliver(to[i], finished, policy, plan, own, scratch, radiance);
            continue;
        }
        // The point waits for its secondary rays, which join the next waves.
        const int node = int(scratch.waiting.size());
        // reflectFactor is only set (and only read) where the point reflects.
        scratch.waiting.push_back({next.color, next.reflects ? next.reflectFactor : glm::vec3(0.f), next.refractWeight,
                                   next.reflects, to[i], root[i], {glm::vec3(0.f), glm::vec3(0.f)}});
        if (next.reflects) {
            scratch.rays[0].push_back(next.reflectRay);
            scratch.routes[0].push_back({p.depth + 1, {node, 0}, root[i]});
        }
        if (next.refracts) {
            scratch.rays[1].push_back(next.refractRay);
            scratch.routes[1].push_back({p.depth + 1, {node, 1}, root[i]});
        }
    }
}

void WhittedIntegrator::deliver(const Destination &to, const glm::vec3 &value, const RayPolicy &policy,
                                const IntegratorPlan &plan, RayCounters &counters, StreamScratch &scratch,
                                std::span<glm::vec3> radiance) const {
    if (to.node >= 0)
        scratch.waiting[size_t(to.node)].secondary[to.index] = value;
    else
        radiance[size_t(to.index)] = finishSample(value, policy, plan, counters);
}

void WhittedIntegrator::radianceFromHits(std::span<const Ray> primaryRays, std::span<const Hit> primaryHits,
                                         uint32_t hitMask, const RayPolicy &policy, const IntegratorPlan &plan,
                                         std::span<RayCounters> counters, std::span<glm::vec3> radiance) const {
    const std::size_t count = primaryRays.size();
    if (count > std::size_t(Tracer::kPacketSize) || primaryHits.size() < count || radiance.size() < count ||
        counters.size() < count)
        throw Error("integrator", "radianceFromHits takes at most " + std::to_string(Tracer::kPacketSize) +
                                      " rays with as many hits, values and counters, not " + std::to_string(count) +
                                      ", " + std::to_string(primaryHits.size()) + ", " +
                                      std::to_string(radiance.size()) + " and " + std::to_string(counters.size()));
    StreamScratch &scratch = threadStreamScratch();
    scratch.waiting.clear();
    for (int kind = 0; kind < 2; ++kind) {
        scratch.rays[kind].clear();
        scratch.routes[kind].clear();
    }

    // Wave 0: the primary points, kept to the end for shown() (edge lines, translucency).
    std::array<ShadingPoint, Tracer::kPacketSize> primary;
    std::array<Destination, Tracer::kPacketSize> to;
    std::array<int, Tracer::kPacketSize> root;
    // A primary ray that missed, with no cap or outline to draw, shows the background through
    // the colour stage: one value for all of them (most rays of a model's frame), computed once
    // with the counts it adds to each.
    const uint32_t missed = ~hitMask & ((1u << count) - 1u); // count ≤ kPacketSize < 32
    RayCounters missCounts;
    glm::vec3 missValue(0.f);
    const bool plainMisses = missed && plainMissRadiance(policy, plan, missValue, missCounts);
    uint32_t lit = 0; // rays whose point goes on to the light loop
    for (std::size_t i = 0; i < count; ++i) {
        RayCounters &own = counters[i];
        countRay(RayType::Primary, own);
        if (plainMisses && ((missed >> i) & 1u)) {
            radiance[i] = missValue;
            own.skippedColorMaps += missCounts.skippedColorMaps;
            own.nonFiniteSamples += missCounts.nonFiniteSamples;
            continue;
        }
        to[i] = {-1, int(i)};
        root[i] = int(i);
        glm::vec3 finished;
        if (prepareShading(primaryRays[i], RayType::Primary, 0, (hitMask >> i) & 1u ? &primaryHits[i] : nullptr,
                           policy, plan, own, 0.f, primary[i], finished))
            lit |= 1u << i;
        else
            radiance[i] = finishSample(finished, policy, plan, own);
    }
    shadeBatch(primary, lit, to.data(), root.data(), policy, plan, counters, scratch, radiance);

    // Later waves: reflected and refracted rays, each kind in packets of up to kPacketSize under
    // its own query; their points are lit as a batch and send their own secondary rays on.
    std::array<ShadingPoint, Tracer::kPacketSize> batch;
    std::size_t read[2] = {0, 0};
    while (read[0] < scratch.rays[0].size() || read[1] < scratch.rays[1].size()) {
        const int kind = read[0] < scratch.rays[0].size() ? 0 : 1;
        const RayType type = kind == 0 ? RayType::Reflection : RayType::Refraction;
        const std::size_t n = std::min(scratch.rays[kind].size() - read[kind], std::size_t(Tracer::kPacketSize));
        // Valid until shadeBatch() below, which adds the next rays (and may move the vector).
        const Ray *rays = scratch.rays[kind].data() + read[kind];
        // The routes are copied: shadeBatch() reads them while it adds routes.
        std::array<Destination, Tracer::kPacketSize> batchTo;
        std::array<int, Tracer::kPacketSize> depth, batchRoot;
        for (std::size_t j = 0; j < n; ++j) {
            const StreamRoute &r = scratch.routes[kind][read[kind] + j];
            batchTo[j] = r.to;
            depth[j] = r.depth;
            batchRoot[j] = r.root;
        }
        read[kind] += n;
        std::array<Hit, Tracer::kPacketSize> &hits = scratch.hits;
        const uint32_t found = m_tracer.closestHits({rays, n}, policy.query(type), {hits.data(), n});
        uint32_t batchLit = 0;
        for (std::size_t j = 0; j < n; ++j) {
            RayCounters &own = counters[size_t(batchRoot[j])];
            countRay(type, own);
            glm::vec3 finished;
            if (prepareShading(rays[j], type, depth[j], (found >> j) & 1u ? &hits[j] : nullptr, policy, plan, own,
                               0.f, batch[j], finished))
                batchLit |= 1u << j;
            else
                deliver(batchTo[j], finished, policy, plan, own, scratch, radiance);
        }
        shadeBatch({batch.data(), n}, batchLit, batchTo.data(), batchRoot.data(), policy, plan, counters, scratch,
                   radiance);
    }

    // Every waiting point was made after the point it reports to, so one pass from the last to
    // the first finds each point's secondary radiance complete.
    for (std::size_t n = scratch.waiting.size(); n-- > 0;) {
        const WaitingPoint &w = scratch.waiting[n];
        const glm::vec3 value = combineSecondary(w.color, w.reflectFactor, w.reflects, w.secondary[0], w.refractWeight,
                                                 w.secondary[1]);
        if (w.to.node >= 0)
            scratch.waiting[size_t(w.to.node)].secondary[w.to.index] = value;
        else
            radiance[size_t(w.to.index)] =
                finishSample(shown(primary[size_t(w.to.index)], value, policy, counters[size_t(w.root)]), policy, plan,
                             counters[size_t(w.root)]);
    }
}

} // namespace mvcl
