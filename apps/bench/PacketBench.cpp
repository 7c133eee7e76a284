// The packet rows of mvcl-bench (PacketBench.h). Both tracers get the same tiles of the same rays;
// each run times one tracer over all tiles, and the two alternate run by run (who goes first
// alternates too), so that a neighbour's load on the shared machine falls on both.

#include "PacketBench.h"

#include "AlternatingRuns.h"
#include "BenchSupport.h"

#include <mvcl/tracer/Hit.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <unistd.h>

namespace mvcl::bench {
namespace {

constexpr int kTile = 4; // 4×4 rays per packet, Tracer::kPacketSize

/// The rays of a list, regrouped into packets of up to 16 (one per 4×4 tile of pixels that has rays).
struct Packets {
    std::vector<Ray> rays;          ///< packet after packet
    std::vector<int> source;        ///< index of each ray in the original list
    std::vector<std::size_t> begin; ///< first ray of each packet; one past the end last
    std::size_t count() const { return begin.size() - 1; }
};

/// Groups rays by the 4×4 tile of the pixel each belongs to (pixel[i] of ray i, ascending).
Packets tilePackets(const std::vector<Ray> &rays, const std::vector<int> &pixel, int width, int height) {
    const int tilesX = (width + kTile - 1) / kTile, tilesY = (height + kTile - 1) / kTile;
    std::vector<std::vector<int>> tiles(std::size_t(tilesX) * std::size_t(tilesY));
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const int x = pixel[i] % width, y = pixel[i] / width;
        tiles[std::size_t(y / kTile) * std::size_t(tilesX) + std::size_t(x / kTile)].push_back(int(i));
    }
    Packets p;
    for (const std::vector<int> &tile : tiles) {
        if (tile.empty()) continue;
        p.begin.push_back(p.rays.size());
        for (const int i : tile) {
            p.rays.push_back(rays[std::size_t(i)]);
            p.source.push_back(i);
        }
    }
    p.begin.push_back(p.rays.size());
    return p;
}

#ifdef MVCL_HAVE_EMBREE
/// One packet of ours as Embree's 16-wide SoA input, lanes past `count` invalid.
void fillEmbreeRays(const Ray *rays, std::size_t count, float tMax, RTCRay16 &ray, int valid[16]) {
    for (int i = 0; i < 16; ++i) {
        const bool live = std::size_t(i) < count;
        valid[i] = live ? -1 : 0;
        const Ray &r = rays[live ? i : 0];
        ray.org_x[i] = r.origin.x, ray.org_y[i] = r.origin.y, ray.org_z[i] = r.origin.z;
        ray.dir_x[i] = r.direction.x, ray.dir_y[i] = r.direction.y, ray.dir_z[i] = r.direction.z;
        ray.tnear[i] = 0.f;
        ray.tfar[i] = tMax;
        ray.time[i] = 0.f;
        ray.mask[i] = ~0u;
        ray.id[i] = unsigned(i);
        ray.flags[i] = 0;
    }
}
#endif

} // namespace

#ifdef MVCL_HAVE_EMBREE
std::string embreeIsaReport() {
    // Embree prints its report on stdout while the device is made: catch it in a temporary file.
    std::fflush(stdout);
    FILE *capture = std::tmpfile();
    if (!capture) return "(no report: tmpfile failed)";
    const int saved = dup(STDOUT_FILENO);
    dup2(fileno(capture), STDOUT_FILENO);
    RTCDevice probe = rtcNewDevice("verbose=1");
    std::fflush(stdout);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    std::string report;
    std::rewind(capture);
    char line[512];
    while (std::fgets(line, sizeof line, capture))
        if (std::strstr(line, "ISA") || std::strstr(line, "Targets")) report += std::string("    ") + line;
    std::fclose(capture);
    if (probe) rtcReleaseDevice(probe);
    return report.empty() ? "    (no ISA lines in Embree's report)\n" : report;
}
#endif

bool runPacketComparison(const PacketBenchInput &in) {
    const Tracer &tracer = *in.tracer;
    const std::vector<Ray> &primary = *in.primary;
    std::vector<int> pixels(primary.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = int(i);
    const Packets primaryPackets = tilePackets(primary, pixels, in.width, in.height);
    const Packets shadowPackets = tilePackets(*in.shadow, *in.shadowPixel, in.width, in.height);
    bool withPeer = false;
#ifdef MVCL_HAVE_EMBREE
    withPeer = in.embree != nullptr;
#endif
    std::printf("\npackets: 4x4 tiles, %zu primary and %zu shadow packets, %d runs each side, alternating\n",
                primaryPackets.count(), shadowPackets.count(), in.repeat);
    std::printf("  ours: single rays %s, packets %s, on %s\n", tracer.singleRayIsa(), tracer.packetIsa(),
                cpuModelName().c_str());
#ifdef MVCL_HAVE_EMBREE
    if (withPeer) std::printf("  embree %s:\n%s", RTC_VERSION_STRING, embreeIsaReport().c_str());
#endif
    constexpr std::size_t kGrain = 16; // packets per work item

    // --- Primary packets ---
    std::vector<Hit> hits(primaryPackets.rays.size());
    std::vector<uint32_t> found(primaryPackets.count());
    auto oursPrimary = [&] {
        parallelForChunks(primaryPackets.count(), in.threads, kGrain, [&](std::size_t b, std::size_t e) {
            for (std::size_t k = b; k < e; ++k) {
                const std::size_t first = primaryPackets.begin[k], n = primaryPackets.begin[k + 1] - first;
                found[k] = tracer.closestHits({primaryPackets.rays.data() + first, n}, in.primaryQuery,
                                              {hits.data() + first, n});
            }
        });
    };
    std::size_t embreeHits = 0;
    auto embreePrimary = [&] {
#ifdef MVCL_HAVE_EMBREE
        std::atomic<std::size_t> total{0};
        parallelForChunks(primaryPackets.count(), in.threads, kGrain, [&](std::size_t b, std::size_t e) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            alignas(64) RTCRayHit16 rh;
            alignas(64) int valid[16];
            std::size_t local = 0;
            for (std::size_t k = b; k < e; ++k) {
                const std::size_t first = primaryPackets.begin[k], n = primaryPackets.begin[k + 1] - first;
                fillEmbreeRays(primaryPackets.rays.data() + first, n, in.primaryQuery.tMax, rh.ray, valid);
                for (int i = 0; i < 16; ++i) rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect16(valid, in.embree, &ctx, &rh);
                for (std::size_t i = 0; i < n; ++i) local += rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
            }
            total += local;
        });
        embreeHits = total.load();
#endif
    };
    Runs oursP, peerP;
    alternate(in.repeat, withPeer, oursPrimary, embreePrimary, oursP, peerP);

    // --- Shadow packets ---
    std::vector<uint32_t> occluded(shadowPackets.count());
    auto oursShadow = [&] {
        parallelForChunks(shadowPackets.count(), in.threads, kGrain, [&](std::size_t b, std::size_t e) {
            for (std::size_t k = b; k < e; ++k) {
                const std::size_t first = shadowPackets.begin[k], n = shadowPackets.begin[k + 1] - first;
                occluded[k] = tracer.anyHits({shadowPackets.rays.data() + first, n}, in.shadowQuery);
            }
        });
    };
    std::size_t embreeOccluded = 0;
    auto embreeShadow = [&] {
#ifdef MVCL_HAVE_EMBREE
        std::atomic<std::size_t> total{0};
        parallelForChunks(shadowPackets.count(), in.threads, kGrain, [&](std::size_t b, std::size_t e) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            alignas(64) RTCRay16 ray;
            alignas(64) int valid[16];
            std::size_t local = 0;
            for (std::size_t k = b; k < e; ++k) {
                const std::size_t first = shadowPackets.begin[k], n = shadowPackets.begin[k + 1] - first;
                fillEmbreeRays(shadowPackets.rays.data() + first, n, in.shadowQuery.tMax, ray, valid);
                rtcOccluded16(valid, in.embree, &ctx, &ray);
                for (std::size_t i = 0; i < n; ++i) local += ray.tfar[i] < 0.f; // −∞ when occluded
            }
            total += local;
        });
        embreeOccluded = total.load();
#endif
    };
    Runs oursS, peerS;
    alternate(in.repeat, withPeer, oursShadow, embreeShadow, oursS, peerS);

    std::printf("primary packets (closestHits vs rtcIntersect16, coherent)\n");
    printRate("ours", primaryPackets.rays.size(), oursP);
    if (withPeer) {
        printRate("embree", primaryPackets.rays.size(), peerP);
        printRatio(oursP, peerP);
    }
    std::printf("shadow packets (anyHits vs rtcOccluded16, coherent)\n");
    printRate("ours", shadowPackets.rays.size(), oursS);
    if (withPeer) {
        printRate("embree", shadowPackets.rays.size(), peerS);
        printRatio(oursS, peerS);
    }

    // The packets must give the single-ray answers bit for bit.
    std::size_t mismatches = 0, packetHits = 0, packetOccluded = 0;
    for (std::size_t k = 0; k < primaryPackets.count(); ++k)
        for (std::size_t i = primaryPackets.begin[k]; i < primaryPackets.begin[k + 1]; ++i) {
            const bool hit = (found[k] >> (i - primaryPackets.begin[k])) & 1u;
            packetHits += hit;
            Hit single;
            const bool expected = tracer.closestHit(primaryPackets.rays[i], in.primaryQuery, single);
            if (hit != expected ||
                (hit && (std::bit_cast<uint32_t>(hits[i].t) != std::bit_cast<uint32_t>(single.t) ||
                         hits[i].geometry != single.geometry || hits[i].primitive != single.primitive ||
                         std::bit_cast<uint32_t>(hits[i].u) != std::bit_cast<uint32_t>(single.u) ||
                         std::bit_cast<uint32_t>(hits[i].v) != std::bit_cast<uint32_t>(single.v))))
                ++mismatches;
        }
    for (std::size_t k = 0; k < shadowPackets.count(); ++k)
        for (std::size_t i = shadowPackets.begin[k]; i < shadowPackets.begin[k + 1]; ++i) {
            const bool occ = (occluded[k] >> (i - shadowPackets.begin[k])) & 1u;
            packetOccluded += occ;
            if (occ != tracer.anyHit(shadowPackets.rays[i], in.shadowQuery)) ++mismatches;
        }
    std::printf("packets vs single rays: %zu mismatches (hits %zu, occluded %zu)", mismatches, packetHits,
                packetOccluded);
    if (withPeer) std::printf("; embree packets: hits %zu, occluded %zu", embreeHits, embreeOccluded);
    std::printf("\n");
    return mismatches == 0;
}

} // namespace mvcl::bench
