#include <mvcl/tracer/Tracer.h>

#include "AnalyticShapes.h"
#include "Bvh.h"
#include "Bvh4.h"
#include "RayContext.h"
#include "WatertightTriangle.h"
#include "WatertightTriangle4.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <thread>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl {

using detail::PrimKind;
using detail::PrimRecord;
using detail::RayContext;

namespace {

/// Traversal stack entries. The binary build bounds the depth (SAH up to 64 levels, then
/// object-median splits of at most 28 more); a 4-wide node pushes at most 3 entries and spans at
/// least one binary level, so 3 · 92 < 320 cannot overflow.
constexpr int kStackSize = 320;

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

/// Robust slab test (Ize 2013). Slabs are taken in the ray's sign order, so a ±0 direction
/// component gives ±∞ distances with the right sign; an origin exactly on a slab plane gives
/// 0·∞ = NaN, which the comparisons below discard (the ray lies in the face: treat as inside).
inline bool intersectBox(const float *b, const RayContext &c, float tHigh, float &tEntry) {
    const float tx0 = (b[c.nearIdx[0]] - c.ray.origin.x) * c.invDir.x;
    const float ty0 = (b[c.nearIdx[1]] - c.ray.origin.y) * c.invDir.y;
    const float tz0 = (b[c.nearIdx[2]] - c.ray.origin.z) * c.invDir.z;
    const float tx1 = (b[c.farIdx[0]] - c.ray.origin.x) * c.invDir.x;
    const float ty1 = (b[c.farIdx[1]] - c.ray.origin.y) * c.invDir.y;
    const float tz1 = (b[c.farIdx[2]] - c.ray.origin.z) * c.invDir.z;
    float tNear = c.tLow;
    tNear = tx0 > tNear ? tx0 : tNear;
    tNear = ty0 > tNear ? ty0 : tNear;
    tNear = tz0 > tNear ? tz0 : tNear;
    float tFar = detail::kInfinity;
    tFar = tx1 < tFar ? tx1 : tFar;
    tFar = ty1 < tFar ? ty1 : tFar;
    tFar = tz1 < tFar ? tz1 : tFar;
    tFar *= detail::kBoxFarScale;
    tEntry = tNear;
    return tNear <= tFar && tNear <= tHigh;
}

/// Offers a candidate to the closest-hit search: it wins if it precedes the best so far in the
/// total order (t, layer, kind, geometry, primitive) and survives the clip volumes.
inline bool offer(const RayContext &c, const Hit &cand, Hit &best) {
    if (!hitPrecedes(cand, best)) return false;
    if (!c.acceptsPoint(cand.t)) return false;
    best = cand;
    return true;
}

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

/// Tests the sphere in lane `lane` of a block. For closest hit (AnyHit = false) updates `best`
/// and returns true if it improved; for any hit returns true on the first accepted hit.
template <bool AnyHit>
inline bool testSphere(const detail::PrimBlock &block, int lane, const detail::PrimInfo &info,
                       const RayContext &c, Hit &best) {
    double roots[2];
    const int n = detail::sphereRoots(c.ray.origin, c.ray.direction, block.vertex(lane, 0),
                                      block.v[1][0][lane], roots);
    for (int i = 0; i < n; ++i) {
        const float t = float(roots[i]);
        if (!c.acceptsT(t)) continue;
        Hit cand;
        cand.t = t;
        cand.kind = GeometryKind::Sphere;
        cand.layer = info.layer;
        cand.geometry = info.geometry;
        cand.primitive = 0;
        if (AnyHit) {
            if (c.acceptsPoint(t)) return true;
            continue;
        }
        // The far root cannot precede the near one, so stop once the near one loses on t;
        // a near root cut away by a clip volume falls through to the far root.
        if (!hitPrecedes(cand, best)) return false;
        if (offer(c, cand, best)) return true;
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

/// Tests the primitives of one leaf. For closest hit (AnyHit = false) updates `best` and returns
/// true if it improved; for any hit returns true on the first accepted hit.
template <bool AnyHit>
inline bool testLeaf(uint32_t leaf, const detail::PrimBlock *blocks, const detail::PrimInfo *info,
                     const RayContext &c, const detail::WatertightRay4 &wray, Hit &best) {
    using detail::Bvh4Leaf;
    const uint32_t first = Bvh4Leaf::firstBlock(leaf);
    const uint32_t last = first + Bvh4Leaf::blockCount(leaf);
    bool found = false;
    for (uint32_t b = first; b < last; ++b) {
        const detail::PrimBlock &block = blocks[b];
        const int lanes = triangleLanes(block, c.layerMask);
        if (!lanes) continue;
        // A stale (larger) cap only lets more candidates reach offer(), which orders them
        // exactly; the t of a lane does not depend on the cap.
        const float tCap = AnyHit ? c.tMax : std::min(c.tMax, best.t);
        detail::TriangleHit4 th;
        int hits = detail::watertightIntersect4(wray, block, lanes, tCap, th);
        while (hits) {
            const int lane = std::countr_zero(unsigned(hits));
            hits &= hits - 1;
            if (!c.acceptsT(th.t[lane])) continue;
            if (AnyHit) {
                if (c.acceptsPoint(th.t[lane])) return true;
                continue;
            }
            found |= offer(c, triangleCandidate(info[4 * b + lane], th.t[lane], th.b1[lane],
                                                th.b2[lane]),
                           best);
        }
    }
    if (Bvh4Leaf::hasSpheres(leaf)) {
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

} // namespace

struct Tracer::Private {
    const Scene &scene;
    TracerSettings settings;
    detail::Bvh4 bvh4; ///< what traversal walks (the binary tree is dropped after the collapse)
    std::vector<PlaneRecord> planes;
    TracerBuildStats stats;

    Private(const Scene &s, const TracerSettings &st) : scene(s), settings(st) {}

    template <bool AnyHit>
    bool traverse(const RayContext &c, Hit &best) const;
    template <bool AnyHit>
    bool testPlanes(const RayContext &c, Hit &best) const;
};

template <bool AnyHit>
bool Tracer::Private::testPlanes(const RayContext &c, Hit &best) const {
    bool found = false;
    for (const PlaneRecord &pl : planes) {
        if (!((c.layerMask >> pl.layer) & 1u)) continue;
        const float t = float(detail::planeT(c.ray.origin, c.ray.direction, pl.normal, pl.offset));
        if (!c.acceptsT(t)) continue;
        Hit cand;
        cand.t = t;
        cand.kind = GeometryKind::Plane;
        cand.layer = pl.layer;
        cand.geometry = pl.geometry;
        cand.primitive = 0;
        if (AnyHit) {
            if (c.acceptsPoint(t)) return true;
            continue;
        }
        found |= offer(c, cand, best);
    }
    return found;
}

/// The per-ray constants of intersectBox4(), broadcast once per query.
struct NodeRay4 {
    const RayContext &c;
#if defined(__SSE2__)
    __m128 ox, oy, oz, ix, iy, iz, tLow;

    explicit NodeRay4(const RayContext &ctx)
        : c(ctx), ox(_mm_set1_ps(ctx.ray.origin.x)), oy(_mm_set1_ps(ctx.ray.origin.y)),
          oz(_mm_set1_ps(ctx.ray.origin.z)), ix(_mm_set1_ps(ctx.invDir.x)),
          iy(_mm_set1_ps(ctx.invDir.y)), iz(_mm_set1_ps(ctx.invDir.z)),
          tLow(_mm_set1_ps(ctx.tLow)) {}
#else
    explicit NodeRay4(const RayContext &ctx) : c(ctx) {}
#endif
};

/// Slab test of the four children of a 4-wide node at once (the same arithmetic as intersectBox,
/// lane by lane). Returns the bit mask of the lanes entered and their entry distances.
inline int intersectBox4(const detail::Bvh4Node &n, const NodeRay4 &r, float tHigh,
                         float tNear4[4]) {
    const RayContext &c = r.c;
#if defined(__SSE2__)
    const __m128 tx0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.bounds[c.nearIdx[0]]), r.ox), r.ix);
    const __m128 ty0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.bounds[c.nearIdx[1]]), r.oy), r.iy);
    const __m128 tz0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.bounds[c.nearIdx[2]]), r.oz), r.iz);
    const __m128 tx1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.bounds[c.farIdx[0]]), r.ox), r.ix);
    const __m128 ty1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.bounds[c.farIdx[1]]), r.oy), r.iy);
    const __m128 tz1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.bounds[c.farIdx[2]]), r.oz), r.iz);
    // maxps/minps return the second operand when either is NaN: the running value survives a
    // 0·∞ lane exactly like the scalar comparisons in intersectBox.
    __m128 tNear = _mm_max_ps(tx0, r.tLow);
    tNear = _mm_max_ps(ty0, tNear);
    tNear = _mm_max_ps(tz0, tNear);
    __m128 tFar = _mm_min_ps(tx1, _mm_set1_ps(detail::kInfinity));
    tFar = _mm_min_ps(ty1, tFar);
    tFar = _mm_min_ps(tz1, tFar);
    tFar = _mm_mul_ps(tFar, _mm_set1_ps(detail::kBoxFarScale));
    const __m128 ok =
        _mm_and_ps(_mm_cmple_ps(tNear, tFar), _mm_cmple_ps(tNear, _mm_set1_ps(tHigh)));
    _mm_storeu_ps(tNear4, tNear);
    const __m128i lm = _mm_and_si128(_mm_load_si128(reinterpret_cast<const __m128i *>(n.layerMask)),
                                     _mm_set1_epi32(int(c.layerMask)));
    const int masked = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(lm, _mm_setzero_si128())));
    return _mm_movemask_ps(ok) & ~masked;
#else
    int bits = 0;
    for (int lane = 0; lane < 4; ++lane) {
        if (!(n.layerMask[lane] & c.layerMask)) continue;
        const float b[6] = {n.bounds[0][lane], n.bounds[1][lane], n.bounds[2][lane],
                            n.bounds[3][lane], n.bounds[4][lane], n.bounds[5][lane]};
        if (intersectBox(b, c, tHigh, tNear4[lane])) bits |= 1 << lane;
    }
    return bits;
#endif
}

template <bool AnyHit>
bool Tracer::Private::traverse(const RayContext &c, Hit &best) const {
    using detail::Bvh4Leaf;
    if (bvh4.blockCount == 0) return false;
    const detail::Bvh4Node *nodes = bvh4.nodes.get();
    const detail::PrimBlock *blocks = bvh4.blocks.get();
    const detail::PrimInfo *info = bvh4.info.data();
    float tHigh = c.tMax * detail::kTraversalSlackUp;
    float tEntry;
    if (!(bvh4.rootMask & c.layerMask) || !intersectBox(bvh4.rootBounds, c, tHigh, tEntry))
        return false;
    // Only now: many rays miss the scene bounds, and the shear costs three divisions.
    const WatertightRay wray(c.ray);
    const detail::WatertightRay4 wray4(wray);
    const NodeRay4 nodeRay(c);

    struct Entry {
        uint32_t ref;
        float t;
    };
    Entry stack[kStackSize];
    int sp = 0;
    uint32_t cur = bvh4.root;
    bool found = false;
    for (;;) {
        if (Bvh4Leaf::isLeaf(cur)) {
            if (testLeaf<AnyHit>(cur, blocks, info, c, wray4, best)) {
                if (AnyHit) return true;
                found = true;
                tHigh = std::min(c.tMax, best.t) * detail::kTraversalSlackUp;
            }
        } else {
            float tNear[4];
            int bits = intersectBox4(nodes[cur], nodeRay, tHigh, tNear);
            if (bits) {
                const uint32_t *child = nodes[cur].child;
                if (AnyHit) {
                    // Any hit ends the query, so ordering the children buys little for the
                    // rays that are blocked and costs every ray that is not.
                    int lane = std::countr_zero(unsigned(bits));
                    bits &= bits - 1;
                    cur = child[lane];
                    while (bits) {
                        lane = std::countr_zero(unsigned(bits));
                        bits &= bits - 1;
                        stack[sp++] = {child[lane], tNear[lane]};
                    }
                    continue;
                }
                Entry hitList[4];
                int k = 0;
                while (bits) {
                    const int lane = std::countr_zero(unsigned(bits));
                    bits &= bits - 1;
                    // Insertion by descending t: the nearest child ends up last.
                    int j = k++;
                    while (j > 0 && hitList[j - 1].t < tNear[lane]) {
                        hitList[j] = hitList[j - 1];
                        --j;
                    }
                    hitList[j] = {child[lane], tNear[lane]};
                }
                for (int i = 0; i + 1 < k; ++i) stack[sp++] = hitList[i];
                cur = hitList[k - 1].ref;
                continue;
            }
        }
        // Pop the nearest pending subtree that can still hold a closer hit.
        for (;;) {
            if (sp == 0) return found;
            const Entry &e = stack[--sp];
            if (e.t <= tHigh) {
                cur = e.ref;
                break;
            }
        }
    }
}

Tracer::Tracer(const Scene &scene, const TracerSettings &settings)
    : d(std::make_unique<Private>(scene, settings)) {
    const auto start = std::chrono::steady_clock::now();

    detail::BvhBuildInput input;
    input.prims.reserve(scene.triangleCount() + scene.spheres.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const TriangleMesh &mesh = scene.meshes[m];
        const uint8_t layer = clampLayer(mesh.layer);
        const std::size_t nv = mesh.positions.size();
        for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
            const glm::uvec3 &tri = mesh.indices[i];
            if (tri.x >= nv || tri.y >= nv || tri.z >= nv) continue;
            const glm::vec3 &p0 = mesh.positions[tri.x];
            const glm::vec3 &p1 = mesh.positions[tri.y];
            const glm::vec3 &p2 = mesh.positions[tri.z];
            if (!isFinite(p0) || !isFinite(p1) || !isFinite(p2) || isDegenerate(p0, p1, p2))
                continue;
            input.prims.push_back(PrimRecord{p0, p1, p2, uint32_t(m), uint32_t(i),
                                             uint8_t(PrimKind::Triangle), layer, 0});
        }
    }
    d->stats.triangles = input.prims.size();
    for (std::size_t s = 0; s < scene.spheres.size(); ++s) {
        const Sphere &sp = scene.spheres[s];
        if (!isFinite(sp.center) || !std::isfinite(sp.radius) || !(sp.radius > 0.f)) continue;
        input.prims.push_back(PrimRecord{sp.center, glm::vec3(sp.radius, 0.f, 0.f), glm::vec3(0.f),
                                         uint32_t(s), 0, uint8_t(PrimKind::Sphere),
                                         clampLayer(sp.layer), 0});
        ++d->stats.spheres;
    }
    for (std::size_t p = 0; p < scene.planes.size(); ++p) {
        const Plane &pl = scene.planes[p];
        const float len = glm::length(pl.normal);
        if (!isFinite(pl.normal) || !std::isfinite(pl.offset) || !(len > 0.f)) continue;
        // Normalised so that t and the error bounds do not depend on how the plane was written.
        d->planes.push_back(
            PlaneRecord{pl.normal / len, pl.offset / len, uint32_t(p), clampLayer(pl.layer)});
    }
    d->stats.planes = d->planes.size();

    input.maxLeafSize = settings.maxLeafSize;
    input.threads = settings.buildThreads > 0 ? settings.buildThreads
                                              : int(std::max(1u, std::thread::hardware_concurrency()));
    {
        const detail::Bvh bvh = detail::buildBvh(std::move(input));
        d->bvh4 = detail::collapseToBvh4(bvh);
        d->stats.leaves = bvh.leafCount;
        d->stats.maxDepth = bvh.maxDepth;
    }
    d->stats.nodes = d->bvh4.nodeCount;
    d->stats.memoryBytes = d->bvh4.nodeCount * sizeof(detail::Bvh4Node) +
                           d->bvh4.blockCount * sizeof(detail::PrimBlock) +
                           d->bvh4.info.size() * sizeof(detail::PrimInfo) +
                           d->planes.size() * sizeof(PlaneRecord);
    d->stats.buildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Tracer::~Tracer() = default;

bool Tracer::closestHit(const Ray &ray, const RayQuery &query, Hit &hit) const {
    if (!detail::isValidQuery(ray, query)) return false;
    const RayContext c(ray, query);
    Hit best;
    bool found = d->traverse<false>(c, best);
    found |= d->testPlanes<false>(c, best);
    if (found) hit = best;
    return found;
}

bool Tracer::anyHit(const Ray &ray, const RayQuery &query) const {
    if (!detail::isValidQuery(ray, query)) return false;
    const RayContext c(ray, query);
    Hit unused;
    return d->testPlanes<true>(c, unused) || d->traverse<true>(c, unused);
}

bool Tracer::closestHitBruteForce(const Ray &ray, const RayQuery &query, Hit &hit) const {
    if (!detail::isValidQuery(ray, query)) return false;
    const RayContext c(ray, query);
    Hit best;
    bool found = false;
    // Every lane through the scalar kernel: this is the oracle the 4-wide kernel is tested against.
    const detail::Bvh4 &bvh4 = d->bvh4;
    const WatertightRay wray(ray);
    for (std::size_t b = 0; b < bvh4.blockCount; ++b) {
        const detail::PrimBlock &block = bvh4.blocks[b];
        for (int lane = 0; lane < 4; ++lane) {
            const detail::PrimInfo &info = bvh4.info[4 * b + lane];
            if (info.kind == uint8_t(PrimKind::Empty) || !((c.layerMask >> info.layer) & 1u))
                continue;
            if (info.kind == uint8_t(PrimKind::Sphere)) {
                found |= testSphere<false>(block, lane, info, c, best);
                continue;
            }
            TriangleHit th;
            if (!detail::watertightIntersect(wray, block.vertex(lane, 0), block.vertex(lane, 1),
                                             block.vertex(lane, 2), std::min(c.tMax, best.t), th))
                continue;
            if (!c.acceptsT(th.t)) continue;
            found |= offer(c, triangleCandidate(info, th.t, th.b1, th.b2), best);
        }
    }
    found |= d->testPlanes<false>(c, best);
    if (found) hit = best;
    return found;
}

SurfaceInteraction Tracer::interaction(const Ray &ray, const Hit &hit) const {
    SurfaceInteraction si;
    const Scene &scene = d->scene;
    switch (hit.kind) {
    case GeometryKind::Triangle: {
        const TriangleMesh &mesh = scene.meshes[hit.geometry];
        const glm::uvec3 tri = mesh.indices[hit.primitive];
        const glm::vec3 &p0 = mesh.positions[tri.x];
        const glm::vec3 &p1 = mesh.positions[tri.y];
        const glm::vec3 &p2 = mesh.positions[tri.z];
        const float b1 = hit.u, b2 = hit.v, b0 = 1.f - b1 - b2;
        // From barycentrics, not o + t·d: the error then scales with the vertices, not with the
        // distance travelled (pbrt-v4 §6.8.5).
        const glm::vec3 q0 = b0 * p0, q1 = b1 * p1, q2 = b2 * p2;
        si.position = q0 + q1 + q2;
        si.positionError = gamma(7) * (glm::abs(q0) + glm::abs(q1) + glm::abs(q2));
        const glm::dvec3 e1 = glm::dvec3(p1) - glm::dvec3(p0);
        const glm::dvec3 e2 = glm::dvec3(p2) - glm::dvec3(p0);
        si.geometricNormal = glm::vec3(glm::normalize(glm::cross(e1, e2)));
        si.shadingNormal = si.geometricNormal;
        if (mesh.normals.size() == mesh.positions.size()) {
            const glm::vec3 ns =
                b0 * mesh.normals[tri.x] + b1 * mesh.normals[tri.y] + b2 * mesh.normals[tri.z];
            const float len = glm::length(ns);
            if (len > 0.f && std::isfinite(len)) {
                si.shadingNormal = ns / len;
                if (glm::dot(si.shadingNormal, si.geometricNormal) < 0.f)
                    si.shadingNormal = -si.shadingNormal;
            }
        }
        si.material = mesh.material;
        si.layer = mesh.layer;
        break;
    }
    case GeometryKind::Sphere: {
        const Sphere &s = scene.spheres[hit.geometry];
        // Reproject onto the sphere in double: the point is then exact up to the final rounding.
        glm::dvec3 pObj = glm::dvec3(ray.origin) - glm::dvec3(s.center) +
                          double(hit.t) * glm::dvec3(ray.direction);
        pObj *= double(s.radius) / glm::length(pObj);
        si.position = glm::vec3(glm::dvec3(s.center) + pObj);
        si.positionError =
            gamma(5) * glm::abs(glm::vec3(pObj)) + gamma(2) * glm::abs(si.position);
        si.geometricNormal = glm::vec3(glm::normalize(pObj));
        si.shadingNormal = si.geometricNormal;
        si.material = s.material;
        si.layer = s.layer;
        break;
    }
    case GeometryKind::Plane: {
        const Plane &pl = scene.planes[hit.geometry];
        const glm::dvec3 n = glm::normalize(glm::dvec3(pl.normal));
        const double len = glm::length(glm::dvec3(pl.normal));
        // o + t·d in double, then projected onto the plane along its normal: the residual error
        // is the float rounding of t (along the ray) and of the result.
        glm::dvec3 p = glm::dvec3(ray.origin) + double(hit.t) * glm::dvec3(ray.direction);
        p -= (glm::dot(n, p) - double(pl.offset) / len) * n;
        si.position = glm::vec3(p);
        const glm::vec3 td = hit.t * ray.direction;
        si.positionError = gamma(3) * (glm::abs(si.position) + glm::abs(td));
        si.geometricNormal = glm::vec3(n);
        si.shadingNormal = si.geometricNormal;
        si.material = pl.material;
        si.layer = pl.layer;
        break;
    }
    }
    return si;
}

const Scene &Tracer::scene() const { return d->scene; }

const TracerBuildStats &Tracer::buildStats() const { return d->stats; }

} // namespace mvcl
