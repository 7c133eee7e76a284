#include <mvcl/tracer/TracerQueryLog.h>

#include <mvcl/core/Error.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/Tracer.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <limits>
#include <string>
#include <mutex>
#include <vector>

namespace mvcl {

namespace {

struct Call {
    uint32_t firstRay;  ///< into rays (and ranges for an any-hit call with ranges)
    uint32_t query;     ///< into queries: the call's layer mask and clip volumes
    float tMin, tMax;   ///< the call's own range (a transparent shadow walk moves it at every step)
    uint8_t rayCount;
    bool anyHit;
    bool hasRanges;     ///< any-hit with a range end per ray
    bool packet;        ///< made through closestHits/anyHits (even of one ray)
};

} // namespace

struct TracerQueryLog::Private {
    mutable std::mutex mutex;
    std::vector<Call> calls;
    std::vector<Ray> rays;
    std::vector<float> ranges; ///< parallel to rays; read for calls with hasRanges
    std::vector<RayQuery> queries;
    std::size_t closestRays = 0, anyRays = 0;

    /// The index of the query's mask and clip volumes among the recorded ones (its range is kept
    /// per call): a frame has a handful, one per policy and ray type.
    uint32_t intern(const RayQuery &query) {
        RayQuery base = query;
        base.tMin = 0.f;
        base.tMax = std::numeric_limits<float>::infinity();
        for (std::size_t i = queries.size(); i-- > 0;)
            if (queries[i] == base) return uint32_t(i);
        queries.push_back(base);
        return uint32_t(queries.size() - 1);
    }

    enum class Kind : uint8_t { ClosestHit, AnyHit };
    enum class Shape : uint8_t { SingleRay, Packet };

    void record(std::span<const Ray> r, const RayQuery &query, std::span<const float> tMax, Kind kind, Shape shape) {
        const bool anyHit = kind == Kind::AnyHit, packet = shape == Shape::Packet;
        if (r.size() > std::size_t(Tracer::kPacketSize))
            throw Error("query log", "a call carries at most " + std::to_string(Tracer::kPacketSize) + " rays");
        const std::lock_guard lock(mutex);
        calls.push_back({uint32_t(rays.size()), intern(query), query.tMin, query.tMax, uint8_t(r.size()), anyHit,
                         !tMax.empty(), packet});
        for (std::size_t i = 0; i < r.size(); ++i) {
            rays.push_back(r[i]);
            ranges.push_back(tMax.empty() ? query.tMax : tMax[i]);
        }
        (anyHit ? anyRays : closestRays) += r.size();
    }
};

TracerQueryLog::TracerQueryLog() : d(std::make_unique<Private>()) {}
TracerQueryLog::~TracerQueryLog() = default;

void TracerQueryLog::recordClosestHit(const Ray &ray, const RayQuery &query) {
    d->record({&ray, 1}, query, {}, Private::Kind::ClosestHit, Private::Shape::SingleRay);
}

void TracerQueryLog::recordClosestHits(std::span<const Ray> rays, const RayQuery &query) {
    d->record(rays, query, {}, Private::Kind::ClosestHit, Private::Shape::Packet);
}

void TracerQueryLog::recordAnyHit(const Ray &ray, const RayQuery &query, float tMax) {
    d->record({&ray, 1}, query, {&tMax, 1}, Private::Kind::AnyHit, Private::Shape::SingleRay);
}

void TracerQueryLog::recordAnyHits(std::span<const Ray> rays, const RayQuery &query, std::span<const float> tMax) {
    d->record(rays, query, tMax, Private::Kind::AnyHit, Private::Shape::Packet);
}

std::size_t TracerQueryLog::closestHitRays() const {
    const std::lock_guard lock(d->mutex);
    return d->closestRays;
}

std::size_t TracerQueryLog::anyHitRays() const {
    const std::lock_guard lock(d->mutex);
    return d->anyRays;
}

std::size_t TracerQueryLog::calls() const {
    const std::lock_guard lock(d->mutex);
    return d->calls.size();
}

std::size_t TracerQueryLog::distinctQueries() const {
    const std::lock_guard lock(d->mutex);
    return d->queries.size();
}

std::size_t TracerQueryLog::replay(const Tracer &tracer, std::size_t first, std::size_t last) const {
    // Read without the lock: replaying while recording is not supported (a benchmark records,
    // then replays).
    last = std::min(last, d->calls.size());
    std::size_t hits = 0;
    std::array<Hit, Tracer::kPacketSize> out;
    // The query is copied only where the mask and clips change from the call before (as a
    // renderer's queries stay put); a new range is two stores.
    RayQuery query;
    uint32_t current = UINT32_MAX;
    for (std::size_t c = first; c < last; ++c) {
        const Call &call = d->calls[c];
        const std::span<const Ray> rays(d->rays.data() + call.firstRay, call.rayCount);
        if (call.query != current) {
            query = d->queries[call.query];
            current = call.query;
        }
        query.tMin = call.tMin;
        query.tMax = call.tMax;
        if (!call.anyHit) {
            if (call.packet)
                hits += std::size_t(std::popcount(tracer.closestHits(rays, query, {out.data(), rays.size()})));
            else
                hits += tracer.closestHit(rays[0], query, out[0]);
        } else if (call.packet) {
            const uint32_t occluded =
                call.hasRanges ? tracer.anyHits(rays, query, {d->ranges.data() + call.firstRay, rays.size()})
                               : tracer.anyHits(rays, query);
            hits += std::size_t(std::popcount(occluded));
        } else {
            hits += tracer.anyHit(rays[0], query, d->ranges[call.firstRay]);
        }
    }
    return hits;
}

void TracerQueryLog::clear() {
    const std::lock_guard lock(d->mutex);
    d->calls.clear();
    d->rays.clear();
    d->ranges.clear();
    d->queries.clear();
    d->closestRays = d->anyRays = 0;
}

} // namespace mvcl
