// Tracer's construction: the scene's triangles, spheres and planes as primitive records (invalid
// ones left out), then the BVH and its collapse to the wide tree the queries walk.

#include "TracerPrivate.h"

#include "Bvh.h"
#include "WideBvh.h"

#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/model/Scene.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

namespace mvcl {

using detail::PrimKind;
using detail::PrimRecord;

namespace {

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

} // namespace

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
    input.pages = settings.bvhQuality == BvhQuality::Quick ? detail::Pages::Small : detail::Pages::HugeWhenLarge;
    input.prims.allocate(triangles + validSpheres.size(), input.pages);
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
            detail::PlaneRecord{pl.normal / len, pl.offset / len, uint32_t(p), clampLayer(pl.layer)});
    }
    d->stats.planes = d->planes.size();
    d->setPlaneFrames();
    for (const Chunk &ch : chunks)
        if (ch.valid) d->layers |= 1u << clampLayer(scene.meshes[ch.mesh].layer);
    for (const uint32_t s : validSpheres) d->layers |= 1u << clampLayer(scene.spheres[s].layer);
    for (const detail::PlaneRecord &pl : d->planes) d->layers |= 1u << pl.layer;
    if (scene.layerContact.isEnabled()) d->contactDistance = scene.layerContact.sceneUnits(scene.bounds());

    input.maxLeafSize = settings.maxLeafSize;
    {
        const detail::Bvh bvh = settings.bvhQuality == BvhQuality::Quick ? detail::buildMortonBvh(std::move(input))
                                                                          : detail::buildBvh(std::move(input));
        d->wide = detail::collapseToWide(bvh, threads);
        d->stats.leaves = bvh.leafCount;
        d->stats.maxDepth = bvh.maxDepth;
    }
    d->stats.bvhQuality = settings.bvhQuality;
    d->stats.nodes = d->wide.nodeCount;
    d->stats.memoryBytes = d->wide.nodeCount * sizeof(detail::WideNode) +
                           d->wide.blockCount * sizeof(detail::PrimBlock) +
                           4 * d->wide.blockCount * sizeof(detail::PrimInfo) +
                           d->planes.size() * sizeof(detail::PlaneRecord);
    d->stats.buildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

namespace {

/// Copies `count` elements of a tree array into new aligned memory.
template <class T>
std::unique_ptr<T[], detail::AlignedFree> copyArray(const std::unique_ptr<T[], detail::AlignedFree> &from,
                                                   std::size_t count) {
    std::unique_ptr<T[], detail::AlignedFree> to(static_cast<T *>(detail::allocateAligned(count * sizeof(T))));
    if (count) std::memcpy(to.get(), from.get(), count * sizeof(T));
    return to;
}

/// The layer masks of the subtree below child reference `ref`, written into its nodes from the
/// leaves' (already relayered) layers; returns the subtree's mask.
uint32_t refreshLayerMasks(detail::WideBvh &wide, uint32_t ref) {
    using detail::WideLeaf;
    if (WideLeaf::isLeaf(ref)) {
        uint32_t mask = 0;
        const std::size_t first = WideLeaf::firstBlock(ref);
        for (std::size_t i = 4 * first; i < 4 * (first + WideLeaf::blockCount(ref)); ++i)
            if (wide.info[i].kind != uint8_t(PrimKind::Empty)) mask |= 1u << wide.info[i].layer;
        return mask;
    }
    detail::WideNode &node = wide.nodes[ref];
    uint32_t mask = 0;
    for (int lane = 0; lane < detail::kWidth; ++lane) {
        if (node.layerMask[lane] == 0) continue; // an empty lane (a real child holds something)
        node.layerMask[lane] = refreshLayerMasks(wide, node.child[lane]);
        mask |= node.layerMask[lane];
    }
    return mask;
}

bool sameGeometryCounts(const Scene &a, const Scene &b) {
    if (a.meshes.size() != b.meshes.size() || a.spheres.size() != b.spheres.size() ||
        a.planes.size() != b.planes.size())
        return false;
    for (std::size_t m = 0; m < a.meshes.size(); ++m)
        if (a.meshes[m].indices.size() != b.meshes[m].indices.size() ||
            a.meshes[m].positions.size() != b.meshes[m].positions.size())
            return false;
    return true;
}

} // namespace

Tracer::Tracer(const Scene &scene, const Tracer &sameGeometry)
    : d(std::make_unique<Private>(scene, sameGeometry.d->settings)) {
    const auto start = std::chrono::steady_clock::now();
    const Private &from = *sameGeometry.d;
    if (!sameGeometryCounts(scene, from.scene))
        throw Error("tracer", "a tracer can take another's BVH only for the same geometry: the scenes differ in "
                              "their meshes, spheres or planes");
    detail::WideBvh &wide = d->wide;
    wide.nodeCount = from.wide.nodeCount;
    wide.blockCount = from.wide.blockCount;
    wide.root = from.wide.root;
    std::copy(std::begin(from.wide.rootBounds), std::end(from.wide.rootBounds), std::begin(wide.rootBounds));
    wide.nodes = copyArray(from.wide.nodes, wide.nodeCount);
    wide.blocks = copyArray(from.wide.blocks, wide.blockCount);
    wide.info = copyArray(from.wide.info, 4 * wide.blockCount);
    // The leaves take the new layers; then the nodes' masks follow from the leaves up.
    parallelFor(wide.blockCount, 0, [&](std::size_t b) {
        for (std::size_t lane = 0; lane < 4; ++lane) {
            detail::PrimInfo &info = wide.info[4 * b + lane];
            if (info.kind == uint8_t(PrimKind::Triangle)) {
                info.layer = clampLayer(scene.meshes[info.geometry].layer);
                wide.blocks[b].triangleLayerBit[lane] = 1u << info.layer;
            } else if (info.kind == uint8_t(PrimKind::Sphere)) {
                info.layer = clampLayer(scene.spheres[info.geometry].layer);
            }
        }
    });
    wide.rootMask = wide.nodeCount + wide.blockCount ? refreshLayerMasks(wide, wide.root) : 0;
    d->planes = from.planes;
    d->setPlaneFrames();
    for (detail::PlaneRecord &pl : d->planes) pl.layer = clampLayer(scene.planes[pl.geometry].layer);
    d->layers = wide.rootMask;
    for (const detail::PlaneRecord &pl : d->planes) d->layers |= 1u << pl.layer;
    if (scene.layerContact.isEnabled()) d->contactDistance = scene.layerContact.sceneUnits(scene.bounds());
    // What this tracer cost: the build it reuses and the copy.
    d->stats = from.stats;
    d->stats.buildMilliseconds +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Tracer::~Tracer() = default;

Bounds3f Tracer::bounds() const {
    Bounds3f box;
    if (d->wide.blockCount == 0) return box;
    const float *b = d->wide.rootBounds; // [min x, min y, min z, max x, max y, max z]
    box.min = {b[0], b[1], b[2]};
    box.max = {b[3], b[4], b[5]};
    return box;
}

} // namespace mvcl
