#pragma once
/// \file TracerQueryLog.h
/// A record of the queries a Tracer answered (closest and any hits, single rays and packets, with
/// their queries and per-ray ranges), so that a benchmark can trace the very same rays again with
/// no shading: the traversal bound of a frame. Attach with Tracer::setQueryLog(); recording is
/// for measurements only (each call takes a lock), never for rendering.

#include <mvcl/core/Export.h>
#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

namespace mvcl {

class Tracer;

class MVCL_EXPORT TracerQueryLog {
public:
    TracerQueryLog();
    ~TracerQueryLog();
    TracerQueryLog(const TracerQueryLog &) = delete;
    TracerQueryLog &operator=(const TracerQueryLog &) = delete;

    /// Tracer::closestHit() of one ray.
    void recordClosestHit(const Ray &ray, const RayQuery &query);
    /// Tracer::closestHits() of a packet.
    void recordClosestHits(std::span<const Ray> rays, const RayQuery &query);
    /// Tracer::anyHit() of one ray, its range ending at min(query.tMax, tMax).
    void recordAnyHit(const Ray &ray, const RayQuery &query, float tMax);
    /// Tracer::anyHits() of a packet; `tMax`, if not empty, holds each ray's range end.
    void recordAnyHits(std::span<const Ray> rays, const RayQuery &query, std::span<const float> tMax);

    /// Recorded rays: closest-hit and any-hit, and the calls that carried them.
    std::size_t closestHitRays() const;
    std::size_t anyHitRays() const;
    std::size_t calls() const;
    /// Distinct queries among the calls (a frame has a handful: one per policy and ray type).
    std::size_t distinctQueries() const;

    /// Traces the calls [first, last) again on `tracer` as they were made (a packet as a packet,
    /// a single ray alone) and returns how many rays hit something, so that the work cannot be
    /// optimised away. Thread-safe: disjoint ranges may be replayed on several threads.
    std::size_t replay(const Tracer &tracer, std::size_t first, std::size_t last) const;

    void clear();

private:
    struct Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
