#pragma once
/// \file Tracer.h
/// The one shared ray tracer of a scene: a BVH over triangles and spheres (planes are tested
/// after traversal), a watertight triangle test, a robust box test, closest-hit and any-hit
/// queries that honour a RayQuery inside traversal. Build once (the constructor); queries are
/// const and thread-safe.

#include <mvcl/core/Export.h>

#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/SurfaceInteraction.h>

#include <cstddef>
#include <memory>

namespace mvcl {

struct Scene;

struct TracerSettings {
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
    double buildMilliseconds = 0.0;
    std::size_t memoryBytes = 0;
};

class MVCL_EXPORT Tracer {
public:
    /// Builds the acceleration structure. The scene must outlive the tracer and not change.
    explicit Tracer(const Scene &scene, const TracerSettings &settings = {});
    ~Tracer();
    Tracer(const Tracer &) = delete;
    Tracer &operator=(const Tracer &) = delete;

    /// Closest hit within the query. Returns false (and leaves `hit` untouched) on a miss.
    /// Invalid rays (NaN/Inf components, zero direction, tMin > tMax) miss.
    bool closestHit(const Ray &ray, const RayQuery &query, Hit &hit) const;
    /// True if anything within the query is hit (shadow rays).
    bool anyHit(const Ray &ray, const RayQuery &query) const;
    /// Same answer as closestHit() by testing every primitive; for tests.
    bool closestHitBruteForce(const Ray &ray, const RayQuery &query, Hit &hit) const;

    /// Position (with error bound), normals, material and layer of a hit.
    SurfaceInteraction interaction(const Ray &ray, const Hit &hit) const;

    const Scene &scene() const;
    const TracerBuildStats &buildStats() const;

private:
    struct MVCL_HIDDEN Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
