// Tracer's queries: closest and any hit for one ray or a packet, with layer priority and the
// contact tolerance, and the brute-force oracle. The walks themselves are the kernels of the
// instruction set the Tracer chose when it was made (Private::singleRays, Private::packets).

#include "TracerPrivate.h"

#include "LayerPriorityHit.h"
#include "LeafIntersection.h"
#include "NearestHit.h"
#include "PacketSetup.h"
#include "RayContext.h"
#include "WatertightTriangle.h"

#include <mvcl/core/Error.h>
#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/TracerQueryLog.h>

#include <glm/vec3.hpp>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <string>

namespace mvcl {

using detail::PrimKind;
using detail::RayContext;

bool Tracer::Private::closestHitInRange(const Ray &ray, const RayQuery &query, Hit &hit, Oracle oracle) const {
    if (oracle == Oracle::Traversal)
        return isLayered(query) ? singleRays.queryLayered(wide, planes.data(), planes.size(), ray, query, query.tMin,
                                                          query.tMax, contactWindow(ray), hit)
                                : singleRays.queryNearest(wide, planes.data(), planes.size(), ray, query, query.tMin,
                                                          query.tMax, hit);
    const RayContext c(ray, query);
    if (isLayered(query)) {
        detail::LayerPriorityHit best(contactWindow(ray));
        return closestHitBruteForce(c, best, hit);
    }
    detail::NearestHit best;
    return closestHitBruteForce(c, best, hit);
}

bool Tracer::Private::anyHitInRange(const Ray &ray, const RayQuery &query) const {
    const RayContext c(ray, query);
    // Any hit ends the query whichever layer it is on: layer priority never changes occlusion.
    detail::NearestHit unused;
    return testPlanes<true>(c, unused) || occluded(c);
}

bool Tracer::Private::touchesOuterLayer(const Tracer &tracer, const Ray &ray, const Hit &hit,
                                        const RayQuery &query) const {
    const uint32_t outer = layers & query.layerMask & (layerBit(hit.layer) - 1u);
    if (!outer) return false;
    const SurfaceInteraction si = tracer.interaction(ray, hit);
    // The segment [p − d·n, p + d·n] through the hit point along its normal, as a ray of its own
    // (the watertight test only reports t > 0). The query's clip volumes apply: a cut-away outer
    // layer is no contact.
    RayQuery probe = query;
    probe.tMin = 0.f;
    probe.tMax = 2.f * contactDistance;
    probe.layerMask = outer;
    const glm::vec3 &n = si.geometricNormal;
    const glm::vec3 back(mulUnfused(contactDistance, n.x), mulUnfused(contactDistance, n.y),
                         mulUnfused(contactDistance, n.z));
    const Ray segment{si.position - back, n};
    return detail::isValidQuery(segment, probe) && anyHitInRange(segment, probe);
}

bool Tracer::Private::closestHitWithContact(const Tracer &tracer, const Ray &ray, const RayQuery &query, Hit &hit,
                                            Oracle oracle) const {
    if (!(contactDistance > 0.f) || !isLayered(query)) return closestHitInRange(ray, query, hit, oracle);
    const int outermost = std::countr_zero(layers & query.layerMask);
    RayQuery rest = query;
    // Each round skips one inner-layer hit that touches an outer layer; a handful covers any
    // real stack of touching layers, and the bound keeps a pathological one finite.
    for (int round = 0; round < kMaxContactSkips; ++round) {
        if (!closestHitInRange(ray, rest, hit, oracle)) return false;
        if (hit.layer == outermost || !touchesOuterLayer(tracer, ray, hit, query)) return true;
        if (!(hit.t < rest.tMax)) return false;
        rest.tMin = nextFloatUp(hit.t);
    }
    return true;
}

bool Tracer::closestHit(const Ray &ray, const RayQuery &query, Hit &hit) const {
    if (TracerQueryLog *log = d->queryLog.load(std::memory_order_relaxed)) log->recordClosestHit(ray, query);
    return d->closestHitQuery(*this, ray, query, query.tMin, query.tMax, hit);
}

bool Tracer::closestHit(const Ray &ray, const RayQuery &query, float tMin, float tMax, Hit &hit) const {
    const float start = std::max(query.tMin, tMin), end = std::min(query.tMax, tMax);
    if (TracerQueryLog *log = d->queryLog.load(std::memory_order_relaxed)) {
        // Recorded as the plain query with this range (only while a log is attached: a copy).
        RayQuery within = query;
        within.tMin = start;
        within.tMax = end;
        log->recordClosestHit(ray, within);
    }
    return d->closestHitQuery(*this, ray, query, start, end, hit);
}

bool Tracer::Private::closestHitQuery(const Tracer &tracer, const Ray &ray, const RayQuery &query, float tMin,
                                      float tMax, Hit &hit) const {
    if (!detail::isValidQuery(ray, tMin, tMax)) return false;
    // One layer: the plain nearest hit, the code and the cost of before layer priority.
    if (!isLayered(query))
        return singleRays.queryNearest(wide, planes.data(), planes.size(), ray, query, tMin, tMax, hit);
    if (!(contactDistance > 0.f))
        return singleRays.queryLayered(wide, planes.data(), planes.size(), ray, query, tMin, tMax, 0.f, hit);
    // The contact tolerance re-queries with a raised tMin: it works on a copy anyway.
    RayQuery within = query;
    within.tMin = tMin;
    within.tMax = tMax;
    return closestHitWithContact(tracer, ray, within, hit, Oracle::Traversal);
}

bool Tracer::anyHit(const Ray &ray, const RayQuery &query) const { return anyHit(ray, query, query.tMax); }

bool Tracer::anyHit(const Ray &ray, const RayQuery &query, float tMax) const {
    if (TracerQueryLog *log = d->queryLog.load(std::memory_order_relaxed)) log->recordAnyHit(ray, query, tMax);
    return d->anyHitQuery(*this, ray, query, tMax);
}

bool Tracer::Private::anyHitQuery(const Tracer &tracer, const Ray &ray, const RayQuery &query, float tMax) const {
    const float end = std::min(query.tMax, tMax);
    if (!detail::isValidQuery(ray, query.tMin, end)) return false;
    if (!(contactDistance > 0.f) || !isLayered(query)) {
        const RayContext c(ray, query, end);
        detail::NearestHit unused;
        return testPlanes<true>(c, unused) || occluded(c);
    }
    // With a contact tolerance an inner layer's surface within the tolerance of an outer layer's
    // does not occlude (the facets of differently triangulated touching layers poke through each
    // other): the outermost layer occludes as always, the others only as a closest hit would
    // show them.
    RayQuery within = query;
    within.tMax = end;
    RayQuery outermost = within;
    outermost.layerMask = layerBit(std::countr_zero(layers & query.layerMask));
    if (anyHitInRange(ray, outermost)) return true;
    Hit unused;
    return closestHitWithContact(tracer, ray, within, unused, Oracle::Traversal);
}

template <class Best, class MakeBest>
uint32_t Tracer::Private::closestHitsInPacket(std::span<const Ray> rays, const RayQuery &query,
                                              std::span<Hit> hits, const MakeBest &makeBest) const {
    detail::PacketSetup s(rays.data(), query);
    packets->load(s, rays.size(), nullptr);
    detail::PacketBests<Best> best;
    for (unsigned rest = s.valid; rest; rest &= rest - 1) new (&best.slot[std::countr_zero(rest)].value) Best(makeBest());
    const unsigned found = tracePacket<false>(s.valid, s, best);
    uint32_t result = 0;
    // Without planes only the rays the walk found something for have a hit to resolve.
    for (unsigned rest = planes.empty() ? found : s.valid; rest; rest &= rest - 1) {
        const int i = std::countr_zero(rest);
        const bool any = ((found >> i) & 1u) | (!planes.empty() && testPlanes<false>(s.context(i), best[i]));
        if (any && best[i].resolve(hits[std::size_t(i)])) result |= 1u << i;
    }
    return result;
}

namespace {
void checkPacketSize(std::size_t rays, std::size_t hits) {
    if (rays > std::size_t(Tracer::kPacketSize))
        throw Error("tracer", "a packet query takes at most " + std::to_string(Tracer::kPacketSize) +
                                  " rays, not " + std::to_string(rays));
    if (hits < rays)
        throw Error("tracer", "a packet query of " + std::to_string(rays) + " rays needs as many hits, not " +
                                  std::to_string(hits));
}
} // namespace

uint32_t Tracer::closestHits(std::span<const Ray> rays, const RayQuery &query, std::span<Hit> hits) const {
    checkPacketSize(rays.size(), hits.size());
    if (TracerQueryLog *log = d->queryLog.load(std::memory_order_relaxed)) log->recordClosestHits(rays, query);
    const bool layered = d->isLayered(query);
    if (layered && d->contactDistance > 0.f) {
        // The contact tolerance re-queries per ray (closestHitWithContact): ray by ray.
        uint32_t result = 0;
        for (std::size_t i = 0; i < rays.size(); ++i)
            if (d->closestHitQuery(*this, rays[i], query, query.tMin, query.tMax, hits[i])) result |= 1u << i;
        return result;
    }
    if (!d->packetsPay()) {
        // Ray by ray, as closestHitQuery() would go for each: the kernel and the plane table are
        // the same for all of them, found once (per ray they cost as much again as a small
        // scene's traversal of a secondary ray).
        const detail::SingleRayKernels &kernels = d->singleRays;
        const detail::PlaneRecord *planes = d->planes.data();
        const std::size_t planeCount = d->planes.size();
        uint32_t result = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (!detail::isValidQuery(rays[i], query.tMin, query.tMax)) continue;
            const bool found = layered ? kernels.queryLayered(d->wide, planes, planeCount, rays[i], query, query.tMin,
                                                              query.tMax, 0.f, hits[i])
                                       : kernels.queryNearest(d->wide, planes, planeCount, rays[i], query, query.tMin,
                                                              query.tMax, hits[i]);
            if (found) result |= 1u << i;
        }
        return result;
    }
    if (layered)
        return d->closestHitsInPacket<detail::LayerPriorityHit>(rays, query, hits,
                                                               [] { return detail::LayerPriorityHit(0.f); });
    return d->closestHitsInPacket<detail::NearestHit>(rays, query, hits, [] { return detail::NearestHit(); });
}

uint32_t Tracer::anyHits(std::span<const Ray> rays, const RayQuery &query) const {
    checkPacketSize(rays.size(), rays.size());
    if (TracerQueryLog *log = d->queryLog.load(std::memory_order_relaxed)) log->recordAnyHits(rays, query, {});
    return d->anyHitsInPacket(*this, rays, query, nullptr);
}

uint32_t Tracer::anyHits(std::span<const Ray> rays, const RayQuery &query, std::span<const float> tMax) const {
    checkPacketSize(rays.size(), rays.size());
    if (tMax.size() < rays.size())
        throw Error("tracer", "a packet query of " + std::to_string(rays.size()) + " rays needs as many ranges, not " +
                                  std::to_string(tMax.size()));
    if (TracerQueryLog *log = d->queryLog.load(std::memory_order_relaxed))
        log->recordAnyHits(rays, query, tMax.first(rays.size()));
    return d->anyHitsInPacket(*this, rays, query, tMax.data());
}

uint32_t Tracer::Private::anyHitsInPacket(const Tracer &tracer, std::span<const Ray> rays, const RayQuery &query,
                                          const float *tMax) const {
    if (!packetsPay() || (contactDistance > 0.f && isLayered(query))) {
        uint32_t result = 0;
        for (std::size_t i = 0; i < rays.size(); ++i)
            if (anyHitQuery(tracer, rays[i], query, tMax ? tMax[i] : query.tMax)) result |= 1u << i;
        return result;
    }
    detail::PacketSetup s(rays.data(), query);
    packets->load(s, rays.size(), tMax);
    detail::UnusedBests unused;
    uint32_t result = 0;
    if (!planes.empty())
        for (unsigned rest = s.valid; rest; rest &= rest - 1) {
            const int i = std::countr_zero(rest);
            if (testPlanes<true>(s.context(i), unused.unused)) result |= 1u << i;
        }
    return result | tracePacket<true>(s.valid & ~result, s, unused);
}

const char *Tracer::singleRayIsa() const { return d->singleRays.name; }

const char *Tracer::packetIsa() const { return d->packets ? d->packets->name : "single rays"; }

bool Tracer::closestHitBruteForce(const Ray &ray, const RayQuery &query, Hit &hit) const {
    if (!detail::isValidQuery(ray, query)) return false;
    return d->closestHitWithContact(*this, ray, query, hit, Private::Oracle::BruteForce);
}

template <class Best>
bool Tracer::Private::closestHitBruteForce(const RayContext &c, Best &best, Hit &hit) const {
    const Ray &ray = c.ray;
    bool found = false;
    // Every lane through the scalar kernel: this is the oracle the 4-wide triangle kernel is tested against.
    const WatertightRay wray(ray);
    for (std::size_t b = 0; b < wide.blockCount; ++b) {
        const detail::PrimBlock &block = wide.blocks[b];
        for (int lane = 0; lane < 4; ++lane) {
            const detail::PrimInfo &info = wide.info[4 * b + lane];
            if (info.kind == uint8_t(PrimKind::Empty) || !((c.layerMask >> info.layer) & 1u))
                continue;
            if (info.kind == uint8_t(PrimKind::Sphere)) {
                found |= detail::testSphere<false>(block, lane, info, c, best);
                continue;
            }
            TriangleHit th;
            if (!detail::watertightIntersect(wray, block.vertex(lane, 0), block.vertex(lane, 1),
                                             block.vertex(lane, 2), std::min(c.tMax, best.cap()), th))
                continue;
            if (!c.acceptsT(th.t)) continue;
            found |= best.offer(c, detail::triangleCandidate(info, th.t, th.b1, th.b2), th.tError);
        }
    }
    found |= testPlanes<false>(c, best);
    return found && best.resolve(hit);
}

const Scene &Tracer::scene() const { return d->scene; }

const TracerBuildStats &Tracer::buildStats() const { return d->stats; }

void Tracer::setQueryLog(TracerQueryLog *log) { d->queryLog.store(log); }

} // namespace mvcl

