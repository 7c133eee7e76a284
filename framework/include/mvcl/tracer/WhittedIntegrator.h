#pragma once
/// \file WhittedIntegrator.h
/// The paper's integrator: Phong (eq. 1) + shadows + mirror reflection + refraction (Snell, total
/// internal reflection, Schlick's Fresnel), bounded depth, background colour. Shadows pass
/// through transparent occluders scaled by their transparency (colourless). Driven per pixel by
/// a RayPolicy (plain data) and the IntegratorPlan of that policy (which stages it needs).

#include <mvcl/core/Bounds3.h>
#include <mvcl/core/Export.h>
#include <mvcl/tracer/IntegratorPlan.h>
#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayCounters.h>
#include <mvcl/tracer/RayPolicy.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace mvcl {

class Tracer;
struct Hit;
struct Scene;
struct RayQuery;
namespace detail {
class MaterialEvaluator;
}

class MVCL_EXPORT WhittedIntegrator {
public:
    /// Reads the scene's layers and materials once (O(meshes + spheres + planes + materials)),
    /// so that plan() costs a few mask operations.
    explicit WhittedIntegrator(const Tracer &tracer);
    ~WhittedIntegrator();
    WhittedIntegrator(const WhittedIntegrator &) = delete;
    WhittedIntegrator &operator=(const WhittedIntegrator &) = delete;

    /// The tracer it traces with.
    const Tracer &tracer() const { return m_tracer; }

    /// The stages `policy` needs in this scene. Compute it once per policy and render pass and
    /// pass it to every radiance() call under that policy.
    IntegratorPlan plan(const RayPolicy &policy, StageSelection selection) const;

    /// Linear RGB radiance along a primary ray under `policy` (colour stage included), running
    /// the stages `plan` (= plan(policy, ...)) asks for.
    glm::vec3 radiance(const Ray &primaryRay, const RayPolicy &policy, const IntegratorPlan &plan,
                       RayCounters &counters) const;
    /// The same, planning the policy on the spot (StageSelection::SkipUnneeded): for single rays
    /// (tests, PixelProbe), not for rendering many rays under one policy.
    glm::vec3 radiance(const Ray &primaryRay, const RayPolicy &policy, RayCounters &counters) const;

    /// radiance() of a primary ray whose closest hit under policy.query(RayType::Primary) is
    /// already known (Tracer::closestHits on a packet of primary rays): `primaryHit` is that hit,
    /// null if the ray missed. The same value bit for bit as radiance(primaryRay, policy, plan,
    /// counters), with the same rays counted.
    glm::vec3 radianceFromHit(const Ray &primaryRay, const Hit *primaryHit, const RayPolicy &policy,
                              const IntegratorPlan &plan, RayCounters &counters) const;

    /// radianceFromHit() of up to Tracer::kPacketSize primary rays under one policy at once
    /// (primaryHits[i] is ray i's hit where bit i of hitMask is set), as a stream: the block's
    /// points are shaded as a batch, the shadow rays of a batch toward each light go as one packet
    /// (Tracer::anyHits with per-ray ranges) where occluders are opaque, and the reflected and
    /// refracted rays of all points form the next waves, traced in packets of their kind
    /// (Tracer::closestHits) down to the trace depth. radiance[i] is the value of
    /// radianceFromHit() for ray i, bit for bit, and counters[i] gets the rays that value cost
    /// (what radianceFromHit() would have added: adaptive sampling weighs a pixel's error by its
    /// cost). Throws mvcl::Error("integrator", ...) for more than Tracer::kPacketSize rays or
    /// fewer hits, values or counters than rays.
    void radianceFromHits(std::span<const Ray> primaryRays, std::span<const Hit> primaryHits, uint32_t hitMask,
                          const RayPolicy &policy, const IntegratorPlan &plan, std::span<RayCounters> counters,
                          std::span<glm::vec3> radiance) const;

    /// What radianceFromHit() gives a primary ray that meets nothing, where that is the same
    /// for every such ray: the background through the colour stage (no outlines, which draw
    /// next to a silhouette, and no capped clip, whose cap a ray can show without a hit). True
    /// with that value and what such a sample adds to the counters besides its primary ray;
    /// false where a miss needs its own ray. For samples known to miss without being traced
    /// (Camera::rasterFootprint of Tracer::bounds()).
    bool plainMissRadiance(const RayPolicy &policy, const IntegratorPlan &plan, glm::vec3 &radiance,
                           RayCounters &counters) const;

private:
    /// Hard ceiling on recursion whatever a policy asks for: keeps the stack bounded (facing
    /// mirrors).
    static constexpr int kDepthCeiling = 64;

    struct ShadingPoint;
    struct LightAnswer;
    struct SecondaryRays;
    struct Destination;
    struct StreamRoute;
    struct WaitingPoint;
    struct StreamScratch;
    /// The calling thread's stream scratch (reused block after block).
    static StreamScratch &threadStreamScratch();

    /// The colour stage and the non-finite check every sample ends with.
    glm::vec3 finishSample(glm::vec3 c, const RayPolicy &policy, const IntegratorPlan &plan,
                           RayCounters &counters) const;
    /// `travelled`: the distance from the camera to the ray's origin (a primary ray continued
    /// through translucent or peeled surfaces), for the depth false colour.
    glm::vec3 trace(const Ray &ray, RayType type, int depth, const RayPolicy &policy,
                    const IntegratorPlan &plan, RayCounters &counters, float travelled = 0.f) const;
    /// trace() from the ray's closest hit under policy.query(type) (null: a miss), the ray
    /// already counted.
    glm::vec3 traceFromHit(const Ray &ray, RayType type, int depth, const Hit *closest, const RayPolicy &policy,
                           const IntegratorPlan &plan, RayCounters &counters, float travelled = 0.f) const;
    /// traceFromHit() up to its light loop: fills `point` and returns true, or returns false with
    /// the final colour in `finished` (a miss, a surface fully peeled, a false colour).
    bool prepareShading(const Ray &ray, RayType type, int depth, const Hit *closest, const RayPolicy &policy,
                        const IntegratorPlan &plan, RayCounters &counters, float travelled, ShadingPoint &point,
                        glm::vec3 &finished) const;
    /// The rest of traceFromHit() up to its secondary rays: lights and shadows. Returns false with
    /// the final colour in `finished`, or true with the reflected and refracted rays to trace in
    /// `next`. `answers`, if not null, holds for each of the first lights its path to the point
    /// and what lightPassing() would answer (shadeBatch() traced those shadow rays as packets).
    /// `shadowBlocked`: shadowBlockedShare(policy.shading), found once per batch.
    bool litColor(const ShadingPoint &point, const RayPolicy &policy, const IntegratorPlan &plan,
                  RayCounters &counters, const LightAnswer *answers, const glm::vec3 &shadowBlocked,
                  SecondaryRays &next, glm::vec3 &finished) const;
    /// The stream's step for up to Tracer::kPacketSize prepared points (bit i of `lit`: points[i]
    /// goes on to the light loop): their shadow rays toward each light as packets, then litColor();
    /// a finished colour goes to to[i], a point with secondary rays waits in `scratch` and its
    /// rays join the next waves. root[i]: the primary ray whose counters[] point i's rays go to.
    void shadeBatch(std::span<ShadingPoint> points, uint32_t lit, const Destination *to, const int *root,
                    const RayPolicy &policy, const IntegratorPlan &plan, std::span<RayCounters> counters,
                    StreamScratch &scratch, std::span<glm::vec3> radiance) const;
    /// Hands a finished value to where it goes: a waiting point's slot, or a primary sample
    /// (through finishSample()).
    void deliver(const Destination &to, const glm::vec3 &value, const RayPolicy &policy, const IntegratorPlan &plan,
                 RayCounters &counters, StreamScratch &scratch, std::span<glm::vec3> radiance) const;
    /// What reaches a point of the light a shadow ray finds blocked, per colour channel: the
    /// policy's shadow strength and tint (the same for every point and light of a policy).
    static glm::vec3 shadowBlockedShare(const ShadingPolicy &shading);
    /// Eq. 1's ambient and direct terms at the point, shadow rays under `shadowQuery` (paths and
    /// answers from `answers` as in litColor()), blocked light scaled by `shadowBlocked`.
    glm::vec3 directLight(const ShadingPoint &point, const IntegratorPlan &plan, RayCounters &counters,
                          const LightAnswer *answers, const RayQuery &shadowQuery,
                          const glm::vec3 &shadowBlocked) const;
    /// A surface colour as the point shows it: edge lines over it, blended over what lies behind.
    glm::vec3 shown(const ShadingPoint &point, const glm::vec3 &surfaceColor, const RayPolicy &policy,
                    RayCounters &counters) const;

    /// Share (0 or 1) of an outline drawn at the primary ray `ray`: probe rays `edges.widthPixels`
    /// apart around it (WhittedIntegratorOutlines.cpp) find a silhouette, a boundary between two
    /// meshes or a crease. `hit` is the ray's own hit under `query`, or null if it missed.
    float outlineCoverage(const Ray &ray, const RayQuery &query, const Hit *hit, const EdgePolicy &edges,
                          RayCounters &counters) const;

    /// True if the point at `t` along `ray` lies inside a closed solid (MeshClosure) of the
    /// layers `query` may hit; `solid` is then the hit where the ray leaves the innermost one.
    /// `firstSurface`, if not null, is the first surface beyond t (found already).
    bool solidAround(const Ray &ray, const RayQuery &query, float t, const Hit *firstSurface, Hit &solid) const;

    /// closestHit() that skips hits an alpha mask cuts out.
    bool closestVisibleHit(const Ray &ray, const RayQuery &query, Hit &hit) const;
    /// From the closest hit `hit`, the first one no alpha mask cuts out (false: none).
    bool skipCutOutHits(const Ray &ray, const RayQuery &query, Hit &hit) const;

    /// Share of a light's intensity (0..1) that reaches the shadow ray's origin.
    float lightPassing(const Ray &shadowRay, float lightDistance, const RayQuery &shadowQuery,
                       ShadowStage stage) const;

    const Tracer &m_tracer;
    /// m_tracer.scene(), kept here: the shading reads it at every point, and Tracer::scene() is a
    /// call into another translation unit.
    const Scene &m_scene;
    /// Textures and alpha of materials at a hit (MaterialEvaluator.cpp).
    std::unique_ptr<detail::MaterialEvaluator> m_materials;
    /// Some material of the scene (used or not) has transparency > 0: forcing every stage walks
    /// every shadow ray's occluders then.
    bool m_hasTransparentMaterials = false;
    /// Layers (bit = layerBit) holding a mesh, sphere or plane.
    uint32_t m_layersWithGeometry = 0;
    /// Layers with geometry whose material may reflect (reflectivity not ≤ 0).
    uint32_t m_layersWithReflectiveMaterial = 0;
    /// Layers with geometry whose material may transmit (transparency not ≤ 0): the only ones
    /// that can pass light into a shadow or spawn refracted rays.
    uint32_t m_layersWithTransmissiveMaterial = 0;
    /// Some material of the scene has an alpha mask that may cut hits out.
    bool m_hasCutOutMaterials = false;
    /// Layers with geometry whose material may be cut out by an alpha mask: shadow rays must
    /// walk past their hits.
    uint32_t m_layersWithCutOutMaterial = 0;
    /// Stripe period of hatched clip caps: 1/160 of the scene's diagonal.
    float m_hatchPeriod = 0.f;
    /// Bounds and layer bit of each closed solid (a sphere, or the meshes of one closed glTF
    /// node and mesh): a point outside all of them is inside none, and no walk is needed.
    struct SolidBounds {
        Bounds3f bounds;
        uint32_t layers = 0;
    };
    std::vector<SolidBounds> m_solidBounds;
};

} // namespace mvcl
