#pragma once
// Private: the state behind a Tracer (Tracer.h), shared by its construction (TracerBuild.cpp) and
// its queries (Tracer.cpp). Baseline code: the kernels of other instruction sets are reached only
// through the tables it holds (KernelTables.h).

#include "AnalyticShapes.h"
#include "KernelTables.h"
#include "LayerPriorityHit.h"
#include "LeafIntersection.h"
#include "NearestHit.h"
#include "PacketSetup.h"
#include "PlaneRecord.h"
#include "RayContext.h"
#include "WideBvh.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace mvcl {

namespace detail {

/// |v| with every product rounded on its own: the contact window must not depend on FMA
/// contraction (FloatBits.h).
inline float lengthUnfused(const glm::vec3 &v) {
    return std::sqrt(mulUnfused(v.x, v.x) + mulUnfused(v.y, v.y) + mulUnfused(v.z, v.z));
}

} // namespace detail

struct Tracer::Private {
    const Scene &scene;
    TracerSettings settings;
    detail::WideBvh wide; ///< what traversal walks (the binary tree is dropped after the collapse)
    /// The compiled variants of traversal this Tracer runs, chosen when it is made (KernelTables.h).
    const detail::SingleRayKernels &singleRays = detail::singleRayKernels();
    const detail::PacketKernels *packets = detail::packetKernels(); ///< null: packets go ray by ray
    std::vector<detail::PlaneRecord> planes;
    /// Each plane of the scene (Scene::planes, valid or not) as Tracer::interaction() projects
    /// hit points onto it, in double: normalize(normal) and offset / length(normal), found once
    /// per plane rather than at every hit (setPlaneFrames()).
    struct PlaneFrame {
        glm::dvec3 unitNormal;
        double offset;
    };
    std::vector<PlaneFrame> planeFrames;
    TracerBuildStats stats;

    /// Bit i set: layer i holds a triangle, sphere or plane. A query reaching one of them only
    /// runs NearestHit, the plain total order: single-layer scenes pay nothing for layer priority.
    uint32_t layers = 0;
    /// Scene::layerContact in scene units (0 = off).
    float contactDistance = 0.f;

    Private(const Scene &s, const TracerSettings &st) : scene(s), settings(st) {}

    /// Fills planeFrames from the scene's planes.
    void setPlaneFrames() {
        planeFrames.clear();
        planeFrames.reserve(scene.planes.size());
        for (const Plane &pl : scene.planes) {
            const glm::dvec3 normal(pl.normal);
            planeFrames.push_back({glm::normalize(normal), double(pl.offset) / glm::length(normal)});
        }
    }

    /// Any hit over the BVH (closest hits go through singleRays.queryNearest and queryLayered).
    bool occluded(const detail::RayContext &c) const {
        detail::NearestHit unused;
        return singleRays.occluded(wide, c, unused);
    }
    /// Only when packetsPay().
    template <bool AnyHit, class Bests>
    unsigned tracePacket(unsigned lanes, detail::PacketSetup &s, Bests &best) const {
        if constexpr (AnyHit) return packets->occluded(wide, lanes, s, best);
        else if constexpr (std::is_same_v<Bests, detail::PacketBests<detail::NearestHit>>)
            return packets->closestNearest(wide, lanes, s, best);
        else return packets->closestLayered(wide, lanes, s, best);
    }
    template <class Best, class MakeBest>
    uint32_t closestHitsInPacket(std::span<const Ray> rays, const RayQuery &query, std::span<Hit> hits,
                                 const MakeBest &makeBest) const;
    template <bool AnyHit, class Best>
    bool testPlanes(const detail::RayContext &c, Best &best) const;
    /// A tree of fewer nodes is walked ray by ray even in packet queries: the packet's set-up
    /// costs more than the few node tests it would share (a scene of a few dozen primitives).
    static constexpr std::size_t kMinPacketNodes = 8;
    bool packetsPay() const { return packets && wide.nodeCount >= kMinPacketNodes; }
    /// Whether the query can reach two or more layers (then layer priority applies).
    bool isLayered(const RayQuery &query) const {
        const uint32_t live = layers & query.layerMask;
        return (live & (live - 1)) != 0;
    }
    /// The contact window of a layered query on `ray` (LayerPriorityHit's, in units of its t).
    float contactWindow(const Ray &ray) const {
        return contactDistance > 0.f ? contactDistance / detail::lengthUnfused(ray.direction) : 0.f;
    }
    /// Tracer::anyHits() with, if `tMax` is not null, each ray's own upper bound.
    uint32_t anyHitsInPacket(const Tracer &tracer, std::span<const Ray> rays, const RayQuery &query,
                             const float *tMax) const;
    template <class Best>
    bool closestHitBruteForce(const detail::RayContext &c, Best &best, Hit &hit) const;

    enum class Oracle { Traversal, BruteForce };
    /// One query (valid) with layer priority where it can reach two layers.
    bool closestHitInRange(const Ray &ray, const RayQuery &query, Hit &hit, Oracle oracle) const;
    bool anyHitInRange(const Ray &ray, const RayQuery &query) const;
    /// With a contact tolerance: whether an inner-layer hit lies within the contact distance of
    /// a surface of an outer layer the query can reach (probed along the hit's normal). Touching
    /// layers triangulated differently poke through each other by up to their facets' sagitta,
    /// also where a ray never meets the outer layer (its silhouette) or leaves it (shadow and
    /// reflection rays spawned from it); such an inner hit is skipped.
    bool touchesOuterLayer(const Tracer &tracer, const Ray &ray, const Hit &hit, const RayQuery &query) const;
    static constexpr int kMaxContactSkips = 16;
    bool closestHitWithContact(const Tracer &tracer, const Ray &ray, const RayQuery &query, Hit &hit,
                               Oracle oracle) const;
    /// Tracer::closestHit() and anyHit() without the query log: what their packet forms call
    /// ray by ray (those calls are logged once, as packets). closestHitQuery runs `query` with the
    /// range [tMin, tMax] instead of its own.
    bool closestHitQuery(const Tracer &tracer, const Ray &ray, const RayQuery &query, float tMin, float tMax,
                         Hit &hit) const;
    bool anyHitQuery(const Tracer &tracer, const Ray &ray, const RayQuery &query, float tMax) const;
    /// Tracer::setQueryLog(): where the public queries are recorded, if anywhere.
    std::atomic<TracerQueryLog *> queryLog{nullptr};
};

template <bool AnyHit, class Best>
bool Tracer::Private::testPlanes(const detail::RayContext &c, Best &best) const {
    return detail::testPlanes<AnyHit>(planes.data(), planes.size(), c, best);
}

} // namespace mvcl
