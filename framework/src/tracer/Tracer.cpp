#include <mvcl/tracer/Tracer.h>

#include "AnalyticShapes.h"
#include "Bvh.h"
#include "LayerPriorityHit.h"
#include "NearestHit.h"
#include "PacketRays.h"
#include "WideBvh.h"
#include "RayContext.h"
#include "TraversalIsa.h"
#include "WatertightTriangle.h"
#include "WatertightTriangle4.h"

#include <mvcl/core/Error.h>
#include <mvcl/core/FloatBits.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/TracerQueryLog.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <new>
#include <type_traits>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// The AVX2 traversal is compiled for its own functions only (#pragma GCC target below), never
// with a global -march flag, and chosen at run time.
#if defined(__GNUC__) && !defined(__clang__) && (defined(__x86_64__) || defined(__i386__))
#define MVCL_HAVE_AVX2_TRAVERSAL 1
#include <immintrin.h>
#else
#define MVCL_HAVE_AVX2_TRAVERSAL 0
#endif

namespace mvcl {

using detail::PrimKind;
using detail::PrimRecord;
using detail::RayContext;

namespace {

/// Traversal stack entries. The binary build bounds the depth (SAH up to 64 levels, then
/// object-median splits of at most 28 more); a wide node pushes at most kWidth − 1 entries and
/// spans at least one binary level, so 7 · 92 < 660 cannot overflow.
constexpr int kStackSize = 660;

struct PlaneRecord {
    glm::vec3 normal;
    float offset;
    uint32_t geometry;
    uint8_t layer;
};

bool isFinite(const glm::vec3 &v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Zero-area test in double: float cross products underflow for tiny but valid triangles.
bool isDegenerate(const glm::vec3 &p0, const glm::vec3 &p1, const glm::vec3 &p2) {
    const glm::dvec3 e1 = glm::dvec3(p1) - glm::dvec3(p0);
    const glm::dvec3 e2 = glm::dvec3(p2) - glm::dvec3(p0);
    const glm::dvec3 n(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                       e1.x * e2.y - e1.y * e2.x);
    return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

uint8_t clampLayer(int layer) { return uint8_t(std::clamp(layer, 0, kMaxLayers - 1)); }

/// |v| with every product rounded on its own: the contact window must not depend on FMA
/// contraction (FloatBits.h).
float lengthUnfused(const glm::vec3 &v) {
    return std::sqrt(mulUnfused(v.x, v.x) + mulUnfused(v.y, v.y) + mulUnfused(v.z, v.z));
}

/// Robust slab test (Ize 2013). Slabs are taken in the ray's sign order, so a ±0 direction
/// component gives ±∞ distances with the right sign; an origin exactly on a slab plane gives
/// 0·∞ = NaN, which the comparisons below discard (the ray lies in the face: treat as inside).
/// The far slabs use invDirFar, which carries the conservative widening (RayContext.h).
inline bool intersectBox(const float *b, const RayContext &c, float tHigh, float &tEntry) {
    const float tx0 = (b[c.nearIdx[0]] - c.ray.origin.x) * c.invDir.x;
    const float ty0 = (b[c.nearIdx[1]] - c.ray.origin.y) * c.invDir.y;
    const float tz0 = (b[c.nearIdx[2]] - c.ray.origin.z) * c.invDir.z;
    const float tx1 = (b[c.farIdx[0]] - c.ray.origin.x) * c.invDirFar.x;
    const float ty1 = (b[c.farIdx[1]] - c.ray.origin.y) * c.invDirFar.y;
    const float tz1 = (b[c.farIdx[2]] - c.ray.origin.z) * c.invDirFar.z;
    // The order of the SIMD node test (maxps(a, b) = a > b ? a : b); tHigh starts the far
    // minimum, as there.
    float tNear = c.tLow;
    tNear = tx0 > tNear ? tx0 : tNear;
    tNear = ty0 > tNear ? ty0 : tNear;
    tNear = tz0 > tNear ? tz0 : tNear;
    float tFar = tHigh;
    tFar = tx1 < tFar ? tx1 : tFar;
    tFar = ty1 < tFar ? ty1 : tFar;
    tFar = tz1 < tFar ? tz1 : tFar;
    tEntry = tNear;
    return tNear <= tFar;
}

/// Error bound of a sphere's or plane's t: the roots are computed in double and rounded to
/// float once, so half an ulp of rounding plus the double arithmetic's far smaller error.
inline float analyticTError(float t) { return gamma(2) * std::fabs(t); }

/// A triangle lane's hit as a candidate Hit (the t range is checked by the caller).
inline Hit triangleCandidate(const detail::PrimInfo &info, float t, float b1, float b2) {
    Hit cand;
    cand.t = t;
    cand.u = b1;
    cand.v = b2;
    cand.kind = GeometryKind::Triangle;
    cand.layer = info.layer;
    cand.geometry = info.geometry;
    cand.primitive = info.primitive;
    return cand;
}

/// A sphere or plane hit: one primitive per geometry, no barycentrics.
inline Hit analyticCandidate(GeometryKind kind, float t, uint8_t layer, uint32_t geometry) {
    Hit cand;
    cand.t = t;
    cand.kind = kind;
    cand.layer = layer;
    cand.geometry = geometry;
    cand.primitive = 0;
    return cand;
}

/// Tests the sphere in lane `lane` of a block. For closest hit (AnyHit = false) offers its hits
/// to `best` and returns true if it changed; for any hit returns true on the first accepted hit.
template <bool AnyHit, class Best>
inline bool testSphere(const detail::PrimBlock &block, int lane, const detail::PrimInfo &info,
                       const RayContext &c, Best &best) {
    double roots[2];
    const int n = detail::sphereRoots(c.ray.origin, c.ray.direction, block.vertex(lane, 0),
                                      block.v[1][0][lane], roots);
    for (int i = 0; i < n; ++i) {
        const float t = float(roots[i]);
        if (!c.acceptsT(t)) continue;
        const Hit cand = analyticCandidate(GeometryKind::Sphere, t, info.layer, info.geometry);
        if (AnyHit) {
            if (c.acceptsPoint(t)) return true;
            continue;
        }
        // The far root cannot do better than the near one, so stop once the near one cannot
        // matter; a near root cut away by a clip volume falls through to the far root.
        if (!best.mayMatter(cand)) return false;
        if (best.offer(c, cand, analyticTError(t))) return true;
    }
    return false;
}

/// Bits of the lanes whose triangle is in one of the query's layers.
inline int triangleLanes(const detail::PrimBlock &block, uint32_t layerMask) {
#if defined(__SSE2__)
    const __m128i bits =
        _mm_and_si128(_mm_load_si128(reinterpret_cast<const __m128i *>(block.triangleLayerBit)),
                      _mm_set1_epi32(int(layerMask)));
    return ~_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(bits, _mm_setzero_si128()))) & 0xf;
#else
    int lanes = 0;
    for (int lane = 0; lane < 4; ++lane)
        if (block.triangleLayerBit[lane] & layerMask) lanes |= 1 << lane;
    return lanes;
#endif
}

/// Tests the primitives of one leaf. For closest hit (AnyHit = false) offers the hits to `best`
/// and returns true if it changed; for any hit returns true on the first accepted hit.
template <bool AnyHit, class Best>
inline bool testLeaf(uint32_t leaf, const detail::PrimBlock *blocks, const detail::PrimInfo *info,
                     const RayContext &c, const detail::WatertightRay4 &wray, Best &best) {
    using detail::WideLeaf;
    const uint32_t first = WideLeaf::firstBlock(leaf);
    const uint32_t last = first + WideLeaf::blockCount(leaf);
    bool found = false;
    for (uint32_t b = first; b < last; ++b) {
        const detail::PrimBlock &block = blocks[b];
        const int lanes = triangleLanes(block, c.layerMask);
        if (!lanes) continue;
        // A stale (larger) cap only lets more candidates reach offer(), which orders them
        // exactly; the t of a lane does not depend on the cap.
        const float tCap = AnyHit ? c.tMax : std::min(c.tMax, best.cap());
        detail::TriangleHit4 th;
        int hits = detail::watertightIntersect4<!AnyHit, !AnyHit && Best::kUsesTError>(wray, block, lanes, tCap, th);
        while (hits) {
            const int lane = std::countr_zero(unsigned(hits));
            hits &= hits - 1;
            if (!c.acceptsT(th.t[lane])) continue;
            if (AnyHit) {
                if (c.acceptsPoint(th.t[lane])) return true;
                continue;
            }
            found |= best.offer(c, triangleCandidate(info[4 * b + lane], th.t[lane], th.b1[lane],
                                                     th.b2[lane]),
                                Best::kUsesTError ? th.tError[lane] : 0.f);
        }
    }
    if (WideLeaf::hasSpheres(leaf)) {
        for (uint32_t b = first; b < last; ++b)
            for (int lane = 0; lane < 4; ++lane) {
                const detail::PrimInfo &pi = info[4 * b + lane];
                if (pi.kind != uint8_t(PrimKind::Sphere) || !((c.layerMask >> pi.layer) & 1u))
                    continue;
                if (testSphere<AnyHit>(blocks[b], lane, pi, c, best)) {
                    if (AnyHit) return true;
                    found = true;
                }
            }
    }
    return found;
}

#define MVCL_TRAVERSAL_NS sse
#define MVCL_TRAVERSAL_AVX2 0
#include "WideTraversal.inl"
#undef MVCL_TRAVERSAL_NS
#undef MVCL_TRAVERSAL_AVX2

#if MVCL_HAVE_AVX2_TRAVERSAL
#pragma GCC push_options
#pragma GCC target("avx2")
#define MVCL_TRAVERSAL_NS avx2
#define MVCL_TRAVERSAL_AVX2 1
#include "WideTraversal.inl"
#undef MVCL_TRAVERSAL_NS
#undef MVCL_TRAVERSAL_AVX2
#pragma GCC pop_options
#endif

/// Storage for a T made later with placement new, left uninitialised until then: arrays of
/// std::optional are zeroed when the struct holding them is made, which cost packet queries
/// as much as their walk. Only for trivially destructible T (never destroyed).
template <class T>
union Slot {
    static_assert(std::is_trivially_destructible_v<T>);
    Slot() {}
    T value;
};

/// A packet query's rays: their origins and directions in lanes, and each ray's context and
/// triangle-kernel constants, made when the ray first reaches a leaf (most rays of a tile that
/// misses the model never do).
struct PacketSetup {
    const Ray *rays = nullptr;
    const RayQuery *query = nullptr;
    /// Each ray's upper bound: the query's, or min(query.tMax, tMax[i]) for anyHits() with
    /// per-ray ranges (the expression a single query with that tMax would hold).
    float tMax[detail::kPacketLanes];
    unsigned valid = 0; ///< rays with a valid query
    unsigned built = 0; ///< rays whose context exists
    unsigned dominantAxisLanes[3] = {}; ///< rays by WatertightRay::kz (the largest |direction| axis)
    detail::PacketRays p;
    Slot<RayContext> contexts[detail::kPacketLanes];
    Slot<WatertightRay> wrayStorage[detail::kPacketLanes];
    Slot<detail::WatertightRay4> wray4s[detail::kPacketLanes];
    // Set by context(i), read only after it.
    const detail::WatertightRay4 *wray4[detail::kPacketLanes];
    const WatertightRay *wrays[detail::kPacketLanes];

    /// `rayTMax`: null, or each ray's own upper bound (see tMax).
    PacketSetup(std::span<const Ray> r, const RayQuery &q, const float *rayTMax = nullptr)
        : rays(r.data()), query(&q) {
        for (int i = 0; i < detail::kPacketLanes; ++i) {
            const bool inPacket = std::size_t(i) < r.size();
            tMax[i] = inPacket && rayTMax ? std::min(q.tMax, rayTMax[i]) : q.tMax;
            // Lanes without a valid ray get harmless constants; no walk ever reads them.
            const bool ok = inPacket && detail::isValidQuery(r[std::size_t(i)], q.tMin, tMax[i]);
            valid |= unsigned(ok) << i;
            const Ray &ray = ok ? r[std::size_t(i)] : Ray{glm::vec3(0.f), glm::vec3(1.f)};
            p.ox[i] = ray.origin.x, p.oy[i] = ray.origin.y, p.oz[i] = ray.origin.z;
            p.dx[i] = ray.direction.x, p.dy[i] = ray.direction.y, p.dz[i] = ray.direction.z;
            // WatertightRay's choice, ties to the lower axis.
            const float ax = std::fabs(ray.direction.x), ay = std::fabs(ray.direction.y), az = std::fabs(ray.direction.z);
            const int kz = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
            dominantAxisLanes[kz] |= unsigned(ok) << i;
        }
    }
    PacketSetup(const PacketSetup &) = delete;
    PacketSetup &operator=(const PacketSetup &) = delete;

    const RayContext &context(int i) {
        if (!((built >> i) & 1u)) {
            new (&contexts[i].value) RayContext(rays[i], *query, tMax[i]);
            wrays[i] = new (&wrayStorage[i].value) WatertightRay(rays[i]);
            wray4[i] = new (&wray4s[i].value) detail::WatertightRay4(*wrays[i]);
            built |= 1u << i;
        }
        return contexts[i].value;
    }
};

#if MVCL_HAVE_AVX2_TRAVERSAL
#pragma GCC push_options
#pragma GCC target("avx2")
#define MVCL_PACKET_NS packet_avx2
#define MVCL_PACKET_AVX512 0
#include "PacketTraversal.inl"
#undef MVCL_PACKET_NS
#undef MVCL_PACKET_AVX512
#pragma GCC pop_options
#pragma GCC push_options
#pragma GCC target("avx512f")
#define MVCL_PACKET_NS packet_avx512
#define MVCL_PACKET_AVX512 1
#include "PacketTraversal.inl"
#undef MVCL_PACKET_NS
#undef MVCL_PACKET_AVX512
#pragma GCC pop_options
#endif

/// Set by tests (TraversalIsa.h) to force the baseline path.
std::atomic<bool> g_forceSseTraversal{false};
std::atomic<detail::PacketIsa> g_packetIsaLimit{detail::PacketIsa::Avx512};

bool useAvx2Traversal() { return !g_forceSseTraversal.load() && detail::avx2TraversalAvailable(); }

detail::PacketIsa choosePacketIsa() {
    return std::min(detail::packetIsaAvailable(), g_packetIsaLimit.load());
}

/// The closest-hit states of a packet's rays, made in place (LayerPriorityHit takes an argument).
template <class Best>
struct PacketBests {
    Slot<Best> slot[detail::kPacketLanes]; ///< made for the valid rays only
    Best &operator[](int i) { return slot[i].value; }
};

/// Any-hit queries need a Best only for the type: one shared, never read.
struct UnusedBests {
    detail::NearestHit unused;
    detail::NearestHit &operator[](int) { return unused; }
};

} // namespace

namespace detail {

void forceSseTraversal(bool force) { g_forceSseTraversal.store(force); }
void limitPacketIsa(PacketIsa isa) { g_packetIsaLimit.store(isa); }
PacketIsa packetIsaAvailable() {
#if MVCL_HAVE_AVX2_TRAVERSAL
    if (__builtin_cpu_supports("avx512f")) return PacketIsa::Avx512;
    if (__builtin_cpu_supports("avx2")) return PacketIsa::Avx2;
#endif
    return PacketIsa::SingleRays;
}
bool avx2TraversalAvailable() {
#if MVCL_HAVE_AVX2_TRAVERSAL
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}
} // namespace detail

struct Tracer::Private {
    const Scene &scene;
    TracerSettings settings;
    detail::WideBvh wide; ///< what traversal walks (the binary tree is dropped after the collapse)
    bool useAvx2 = useAvx2Traversal(); ///< which compiled variant of traverse() runs
    detail::PacketIsa packetIsa = choosePacketIsa(); ///< which variant of tracePacket() runs
    std::vector<PlaneRecord> planes;
    TracerBuildStats stats;

    /// Bit i set: layer i holds a triangle, sphere or plane. A query reaching one of them only
    /// runs NearestHit, the plain total order: single-layer scenes pay nothing for layer priority.
    uint32_t layers = 0;
    /// Scene::layerContact in scene units (0 = off).
    float contactDistance = 0.f;

    Private(const Scene &s, const TracerSettings &st) : scene(s), settings(st) {}

    template <bool AnyHit, class Best>
    bool traverse(const RayContext &c, Best &best) const {
#if MVCL_HAVE_AVX2_TRAVERSAL
        if (useAvx2) return avx2::traverse<AnyHit>(wide, c, best);
#endif
        return sse::traverse<AnyHit>(wide, c, best);
    }
    template <bool AnyHit, class Bests>
    unsigned tracePacket(unsigned lanes, PacketSetup &s, Bests &best) const {
#if MVCL_HAVE_AVX2_TRAVERSAL
        if (packetIsa == detail::PacketIsa::Avx512) return packet_avx512::tracePacket<AnyHit>(wide, lanes, s, best);
        return packet_avx2::tracePacket<AnyHit>(wide, lanes, s, best);
#else
        (void)lanes, (void)s, (void)best;
        return 0;
#endif
    }
    template <class Best, class MakeBest>
    uint32_t closestHitsInPacket(std::span<const Ray> rays, const RayQuery &query, std::span<Hit> hits,
                                 const MakeBest &makeBest) const;
    template <bool AnyHit, class Best>
    bool testPlanes(const RayContext &c, Best &best) const;
    /// A tree of fewer nodes is walked ray by ray even in packet queries: the packet's set-up
    /// costs more than the few node tests it would share (a scene of a few dozen primitives).
    static constexpr std::size_t kMinPacketNodes = 8;
    bool packetsPay() const { return packetIsa != detail::PacketIsa::SingleRays && wide.nodeCount >= kMinPacketNodes; }
    /// Whether the query can reach two or more layers (then layer priority applies).
    bool isLayered(const RayQuery &query) const {
        const uint32_t live = layers & query.layerMask;
        return (live & (live - 1)) != 0;
    }
    /// The closest-hit state for a layered query on `ray`.
    detail::LayerPriorityHit layerPriority(const Ray &ray) const {
        return detail::LayerPriorityHit(contactDistance > 0.f ? contactDistance / lengthUnfused(ray.direction) : 0.f);
    }
    /// Tracer::anyHits() with, if `tMax` is not null, each ray's own upper bound.
    uint32_t anyHitsInPacket(const Tracer &tracer, std::span<const Ray> rays, const RayQuery &query,
                             const float *tMax) const;
    template <class Best>
    bool closestHit(const RayContext &c, Best &best, Hit &hit) const {
        bool found = traverse<false>(c, best);
        found |= testPlanes<false>(c, best);
        return found && best.resolve(hit);
    }
    template <class Best>
    bool closestHitBruteForce(const RayContext &c, Best &best, Hit &hit) const;

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
    /// ray by ray (those calls are logged once, as packets).
    bool closestHitQuery(const Tracer &tracer, const Ray &ray, const RayQuery &query, Hit &hit) const;
    bool anyHitQuery(const Tracer &tracer, const Ray &ray, const RayQuery &query, float tMax) const;
    /// Tracer::setQueryLog(): where the public queries are recorded, if anywhere.
    std::atomic<TracerQueryLog *> queryLog{nullptr};
};

template <bool AnyHit, class Best>
bool Tracer::Private::testPlanes(const RayContext &c, Best &best) const {
    bool found = false;
    for (const PlaneRecord &pl : planes) {
        if (!((c.layerMask >> pl.layer) & 1u)) continue;
        const float t = float(detail::planeT(c.ray.origin, c.ray.direction, pl.normal, pl.offset));
        if (!c.acceptsT(t)) continue;
        const Hit cand = analyticCandidate(GeometryKind::Plane, t, pl.layer, pl.geometry);
        if (AnyHit) {
            if (c.acceptsPoint(t)) return true;
            continue;
        }
        found |= best.offer(c, cand, analyticTError(t));
    }
    return found;
}

Tracer::Tracer(const Scene &scene, const TracerSettings &settings)
    : d(std::make_unique<Private>(scene, settings)) {
    const auto start = std::chrono::steady_clock::now();

    const int threads = settings.buildThreads > 0 ? settings.buildThreads : workerThreadCount();
    detail::BvhBuildInput input;
    input.threads = threads;
    // Triangles in chunks of at most kChunk of one mesh: a parallel pass counts each chunk's
    // valid triangles, a prefix sum places the chunks, a second parallel pass writes them, so
    // the records come out in mesh and index order whatever the thread count.
    struct Chunk {
        uint32_t mesh, begin, end;
        std::size_t valid = 0, offset = 0;
    };
    constexpr uint32_t kChunk = 16384;
    std::vector<Chunk> chunks;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const std::size_t count = scene.meshes[m].indices.size();
        for (std::size_t b = 0; b < count; b += kChunk)
            chunks.push_back(Chunk{uint32_t(m), uint32_t(b), uint32_t(std::min<std::size_t>(count, b + kChunk))});
    }
    // Calls emit(index, p0, p1, p2) for every valid triangle of the chunk, in order.
    auto forValid = [&scene](const Chunk &ch, auto &&emit) {
        const TriangleMesh &mesh = scene.meshes[ch.mesh];
        const std::size_t nv = mesh.positions.size();
        for (uint32_t i = ch.begin; i < ch.end; ++i) {
            const glm::uvec3 &tri = mesh.indices[i];
            if (tri.x >= nv || tri.y >= nv || tri.z >= nv) continue;
            const glm::vec3 &p0 = mesh.positions[tri.x];
            const glm::vec3 &p1 = mesh.positions[tri.y];
            const glm::vec3 &p2 = mesh.positions[tri.z];
            if (!isFinite(p0) || !isFinite(p1) || !isFinite(p2) || isDegenerate(p0, p1, p2))
                continue;
            emit(i, p0, p1, p2);
        }
    };
    parallelFor(chunks.size(), threads, [&](std::size_t c) {
        forValid(chunks[c], [&](uint32_t, const glm::vec3 &, const glm::vec3 &, const glm::vec3 &) {
            ++chunks[c].valid;
        });
    });
    std::size_t triangles = 0;
    for (Chunk &ch : chunks) {
        ch.offset = triangles;
        triangles += ch.valid;
    }
    std::vector<uint32_t> validSpheres;
    for (std::size_t s = 0; s < scene.spheres.size(); ++s) {
        const Sphere &sp = scene.spheres[s];
        if (isFinite(sp.center) && std::isfinite(sp.radius) && sp.radius > 0.f)
            validSpheres.push_back(uint32_t(s));
    }
    input.prims.allocate(triangles + validSpheres.size());
    parallelFor(chunks.size(), threads, [&](std::size_t c) {
        const Chunk &ch = chunks[c];
        const uint8_t layer = clampLayer(scene.meshes[ch.mesh].layer);
        std::size_t out = ch.offset;
        forValid(ch, [&](uint32_t i, const glm::vec3 &p0, const glm::vec3 &p1, const glm::vec3 &p2) {
            input.prims[out++] = PrimRecord{p0, p1, p2, ch.mesh, i, uint8_t(PrimKind::Triangle), layer, 0};
        });
    });
    d->stats.triangles = triangles;
    for (std::size_t k = 0; k < validSpheres.size(); ++k) {
        const Sphere &sp = scene.spheres[validSpheres[k]];
        input.prims[triangles + k] =
            PrimRecord{sp.center, glm::vec3(sp.radius, 0.f, 0.f), glm::vec3(0.f), validSpheres[k],
                       0, uint8_t(PrimKind::Sphere), clampLayer(sp.layer), 0};
    }
    d->stats.spheres = validSpheres.size();
    for (std::size_t p = 0; p < scene.planes.size(); ++p) {
        const Plane &pl = scene.planes[p];
        const float len = glm::length(pl.normal);
        if (!isFinite(pl.normal) || !std::isfinite(pl.offset) || !(len > 0.f)) continue;
        // Normalised so that t and the error bounds do not depend on how the plane was written.
        d->planes.push_back(
            PlaneRecord{pl.normal / len, pl.offset / len, uint32_t(p), clampLayer(pl.layer)});
    }
    d->stats.planes = d->planes.size();
    for (const Chunk &ch : chunks)
        if (ch.valid) d->layers |= 1u << clampLayer(scene.meshes[ch.mesh].layer);
    for (const uint32_t s : validSpheres) d->layers |= 1u << clampLayer(scene.spheres[s].layer);
    for (const PlaneRecord &pl : d->planes) d->layers |= 1u << pl.layer;
    if (scene.layerContact.isEnabled()) d->contactDistance = scene.layerContact.sceneUnits(scene.bounds());

    input.maxLeafSize = settings.maxLeafSize;
    {
        const detail::Bvh bvh = detail::buildBvh(std::move(input));
        d->wide = detail::collapseToWide(bvh, threads);
        d->stats.leaves = bvh.leafCount;
        d->stats.maxDepth = bvh.maxDepth;
    }
    d->stats.nodes = d->wide.nodeCount;
    d->stats.memoryBytes = d->wide.nodeCount * sizeof(detail::WideNode) +
                           d->wide.blockCount * sizeof(detail::PrimBlock) +
                           4 * d->wide.blockCount * sizeof(detail::PrimInfo) +
                           d->planes.size() * sizeof(PlaneRecord);
    d->stats.buildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Tracer::~Tracer() = default;

bool Tracer::Private::closestHitInRange(const Ray &ray, const RayQuery &query, Hit &hit, Oracle oracle) const {
    const RayContext c(ray, query);
    if (isLayered(query)) {
        detail::LayerPriorityHit best = layerPriority(ray);
        return oracle == Oracle::BruteForce ? closestHitBruteForce(c, best, hit) : closestHit(c, best, hit);
    }
    detail::NearestHit best;
    return oracle == Oracle::BruteForce ? closestHitBruteForce(c, best, hit) : closestHit(c, best, hit);
}

bool Tracer::Private::anyHitInRange(const Ray &ray, const RayQuery &query) const {
    const RayContext c(ray, query);
    // Any hit ends the query whichever layer it is on: layer priority never changes occlusion.
    detail::NearestHit unused;
    return testPlanes<true>(c, unused) || traverse<true>(c, unused);
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
    return d->closestHitQuery(*this, ray, query, hit);
}

bool Tracer::Private::closestHitQuery(const Tracer &tracer, const Ray &ray, const RayQuery &query, Hit &hit) const {
    if (!detail::isValidQuery(ray, query)) return false;
    if (!isLayered(query)) {
        // One layer: the plain nearest hit, the code and the cost of before layer priority.
        const RayContext c(ray, query);
        detail::NearestHit best;
        return closestHit(c, best, hit);
    }
    if (!(contactDistance > 0.f)) {
        const RayContext c(ray, query);
        detail::LayerPriorityHit best(0.f);
        return closestHit(c, best, hit);
    }
    return closestHitWithContact(tracer, ray, query, hit, Oracle::Traversal);
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
        return testPlanes<true>(c, unused) || traverse<true>(c, unused);
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
    PacketSetup s(rays, query);
    PacketBests<Best> best;
    for (unsigned rest = s.valid; rest; rest &= rest - 1) new (&best.slot[std::countr_zero(rest)].value) Best(makeBest());
    const unsigned found = tracePacket<false>(s.valid, s, best);
    uint32_t result = 0;
    for (unsigned rest = s.valid; rest; rest &= rest - 1) {
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
    if (!d->packetsPay() || (layered && d->contactDistance > 0.f)) {
        // The contact tolerance re-queries per ray (closestHitWithContact): ray by ray.
        uint32_t result = 0;
        for (std::size_t i = 0; i < rays.size(); ++i)
            if (d->closestHitQuery(*this, rays[i], query, hits[i])) result |= 1u << i;
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
    PacketSetup s(rays, query, tMax);
    UnusedBests unused;
    uint32_t result = 0;
    if (!planes.empty())
        for (unsigned rest = s.valid; rest; rest &= rest - 1) {
            const int i = std::countr_zero(rest);
            if (testPlanes<true>(s.context(i), unused.unused)) result |= 1u << i;
        }
    return result | tracePacket<true>(s.valid & ~result, s, unused);
}

const char *Tracer::singleRayIsa() const { return d->useAvx2 ? "avx2" : "sse2"; }

const char *Tracer::packetIsa() const {
    switch (d->packetIsa) {
    case detail::PacketIsa::Avx512: return "avx512";
    case detail::PacketIsa::Avx2: return "avx2";
    case detail::PacketIsa::SingleRays: break;
    }
    return "single rays";
}

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
                found |= testSphere<false>(block, lane, info, c, best);
                continue;
            }
            TriangleHit th;
            if (!detail::watertightIntersect(wray, block.vertex(lane, 0), block.vertex(lane, 1),
                                             block.vertex(lane, 2), std::min(c.tMax, best.cap()), th))
                continue;
            if (!c.acceptsT(th.t)) continue;
            found |= best.offer(c, triangleCandidate(info, th.t, th.b1, th.b2), th.tError);
        }
    }
    found |= testPlanes<false>(c, best);
    return found && best.resolve(hit);
}

const Scene &Tracer::scene() const { return d->scene; }

const TracerBuildStats &Tracer::buildStats() const { return d->stats; }

void Tracer::setQueryLog(TracerQueryLog *log) { d->queryLog.store(log); }

} // namespace mvcl
