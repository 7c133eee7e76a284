#include <mvcl/tracer/WhittedIntegrator.h>

// What the integrator knows of its scene and how it walks along one ray: construction (what the
// materials of each layer may do, the bounds of closed solids), plan(), and the walks past alpha
// cut-outs, through transparent occluders (shadows) and out of closed solids (clip caps).

#include "MaterialEvaluator.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace mvcl {

namespace {

// Alpha-masked hits a ray skips before it gives up and takes the background (foliage cards).
constexpr int kMaxCutOutHits = 64;

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

} // namespace

WhittedIntegrator::WhittedIntegrator(const Tracer &tracer)
    : m_tracer(tracer), m_scene(tracer.scene()), m_materials(std::make_unique<detail::MaterialEvaluator>(tracer.scene())) {
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
                                      ShadowStage stage) const {
    // Opaque occluders need only "is anything in the way" (any-hit, the cheap query).
    if (stage != ShadowStage::TransparentWalk) return m_tracer.anyHit(shadowRay, shadowQuery, lightDistance) ? 0.f : 1.f;
    // Transparent occluders let their transparency through (Whitted's transparent shadows):
    // walk the hits along the same ray, each step starting just past the previous hit. The steps
    // pass their range beside the query, not in a copy of it (its clip volumes are 600 bytes).
    const float tMax = std::min(shadowQuery.tMax, lightDistance);
    float tMin = shadowQuery.tMin;
    constexpr int kMaxOccluders = 16;
    float passed = 1.f;
    for (int i = 0; i < kMaxOccluders; ++i) {
        Hit hit;
        if (!m_tracer.closestHit(shadowRay, shadowQuery, tMin, tMax, hit)) return passed;
        passed *= m_materials->transmittance(hit);
        if (passed <= 0.f) return 0.f;
        tMin = nextFloatUp(hit.t);
        if (tMin > tMax) return passed;
    }
    return 0.f; // more occluders than we follow: treat the light as blocked
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

} // namespace mvcl
