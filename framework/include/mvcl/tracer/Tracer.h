#pragma once
/// \file Tracer.h
/// The one shared ray tracer of a scene: a BVH over triangles and spheres (planes are tested
/// after traversal), a watertight triangle test, a robust box test, closest-hit and any-hit
/// queries that honour a RayQuery inside traversal. Build once (the constructor); queries are
/// const and thread-safe.

#include <mvcl/core/Bounds3.h>
#include <mvcl/core/Export.h>

#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/SurfaceInteraction.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

namespace mvcl {

struct Scene;
class TracerQueryLog;

/// How the BVH is built: what a query costs against what the build costs. Every quality gives
/// the same answers (the same hits, the same images); only the speed differs.
enum class BvhQuality {
    /// Sorted along a Morton curve, split by the codes' bits: builds several times faster than
    /// Full and traces slower. For a first image of a large model while a full build runs.
    Quick,
    /// Binned surface-area heuristic: the fastest queries.
    Full,
};

struct TracerSettings {
    BvhQuality bvhQuality = BvhQuality::Full;
    /// Leaves hold at most this many primitives.
    int maxLeafSize = 4;
    /// Threads for the build (0 = all cores).
    int buildThreads = 0;
};

struct TracerBuildStats {
    std::size_t triangles = 0; ///< triangles in the BVH (degenerate ones are left out)
    std::size_t spheres = 0;
    std::size_t planes = 0;
    std::size_t nodes = 0;
    std::size_t leaves = 0;
    int maxDepth = 0;
    BvhQuality bvhQuality = BvhQuality::Full;
    double buildMilliseconds = 0.0; ///< with Tracer(scene, sameGeometry): that build plus the copy
    std::size_t memoryBytes = 0;
};

class MVCL_EXPORT Tracer {
public:
    /// Builds the acceleration structure. The scene must outlive the tracer and not change.
    explicit Tracer(const Scene &scene, const TracerSettings &settings = {});
    /// A tracer over `scene` that reuses the BVH of `sameGeometry` instead of building one:
    /// `scene` must hold the same geometry as the scene `sameGeometry` was built over (the same
    /// meshes, spheres and planes) and may differ in their layers and in its layer contact.
    /// Layer inference runs on a tracer of the scene as read and then moves meshes between
    /// layers; this gives the tracer of the result in a copy of the arrays, not a second build.
    /// Throws mvcl::Error("tracer", …) when the geometry visibly differs (other counts).
    Tracer(const Scene &scene, const Tracer &sameGeometry);
    ~Tracer();
    Tracer(const Tracer &) = delete;
    Tracer &operator=(const Tracer &) = delete;

    /// Closest hit within the query. Returns false (and leaves `hit` untouched) on a miss.
    /// Invalid rays (NaN/Inf components, zero direction, tMin > tMax) miss.
    bool closestHit(const Ray &ray, const RayQuery &query, Hit &hit) const;
    /// closestHit() with the range [max(query.tMin, tMin), min(query.tMax, tMax)]: the steps of a
    /// walk along one ray (a transparent shadow ray, each step starting past the previous hit),
    /// without a copy of the query.
    bool closestHit(const Ray &ray, const RayQuery &query, float tMin, float tMax, Hit &hit) const;
    /// True if anything within the query is hit (shadow rays).
    bool anyHit(const Ray &ray, const RayQuery &query) const;
    /// anyHit() with the range ending at min(query.tMax, tMax): a shadow ray toward a point light
    /// at distance tMax, without a copy of the query.
    bool anyHit(const Ray &ray, const RayQuery &query, float tMax) const;
    /// Most rays a packet query takes: a 4×4 tile.
    static constexpr int kPacketSize = 16;
    /// closestHit() of each ray under one shared query, traced together as a packet: for coherent
    /// rays (the primary rays of a tile), which then share the walk down the BVH. The hits are
    /// those of closestHit() ray by ray, bit for bit. Returns the bit mask of the rays that hit
    /// (bit i: rays[i]; hits[i] is written for those only). Throws mvcl::Error("tracer", ...) when
    /// rays.size() > kPacketSize or hits.size() < rays.size().
    uint32_t closestHits(std::span<const Ray> rays, const RayQuery &query, std::span<Hit> hits) const;
    /// anyHit() of each ray under one shared query, as a packet (shadow rays of a tile toward one
    /// light). Returns the bit mask of the occluded rays; same answers as anyHit() ray by ray.
    uint32_t anyHits(std::span<const Ray> rays, const RayQuery &query) const;
    /// anyHits() where ray i's range ends at min(query.tMax, tMax[i]): shadow rays toward a point
    /// light, each as long as its distance to the light. Same answers as anyHit() ray by ray under
    /// the query with that tMax. Also throws when tMax.size() < rays.size().
    uint32_t anyHits(std::span<const Ray> rays, const RayQuery &query, std::span<const float> tMax) const;

    /// The instruction set traversal uses on this CPU, for benches and logs: "avx2" or "sse2"
    /// for single rays; "avx512", "avx2" or "single rays" (no packet code for this CPU) for packets.
    const char *singleRayIsa() const;
    const char *packetIsa() const;

    /// Same answer as closestHit() by testing every primitive; for tests.
    bool closestHitBruteForce(const Ray &ray, const RayQuery &query, Hit &hit) const;

    /// Position (with error bound), normals, material and layer of a hit.
    SurfaceInteraction interaction(const Ray &ray, const Hit &hit) const;

    /// The box around every primitive the BVH holds (triangles and spheres; empty when it holds
    /// none): a ray that misses it can only meet the scene's planes, which are unbounded and
    /// not in it. For leaving out whole groups of rays before they are made
    /// (Camera::rasterFootprint).
    Bounds3f bounds() const;

    const Scene &scene() const;
    const TracerBuildStats &buildStats() const;

    /// While `log` is set (not null), every closestHit, anyHit, closestHits and anyHits call is
    /// appended to it (a packet as one call), so that a benchmark can trace a frame's rays again
    /// without shading. For measurements: recording takes a lock per call. Set it while no query
    /// runs; the log must outlive its use. Null (the default) records nothing.
    void setQueryLog(TracerQueryLog *log);

private:
    struct MVCL_HIDDEN Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
