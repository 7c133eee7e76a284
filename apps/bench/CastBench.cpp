// mvcl-bench cast: identical primary rays for us and any other tracer (the rays are defined in
// CastRays.h and docs/benchmarks.md), cast with closestHit and, with --peer, with Embree's
// rtcIntersect1 on the same triangles.

#include "CastBench.h"

#include "BenchSupport.h"
#include "CastRays.h"
#include "CommandLineValues.h"
#include "EmbreePeer.h"

#include <mvcl/core/Error.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace mvcl::bench {
namespace {

struct CastOptions {
    std::string model = "tests/data/models/2CylinderEngine/2CylinderEngine.glb";
    std::optional<CastCamera> camera; ///< default: a three-quarter view framing the scene
    int width = 1024;
    int height = 1024;
    int threads = 0;
    int repeat = 3;
    bool withPeer = false;
};

const char *kCastUsage =
    "usage: mvcl-bench cast [model | builtin:NAME] [--camera EYE,TARGET,UP,FOVY] [--size WxH]\n"
    "                       [--threads N] [--repeat R] [--peer]";

std::optional<CastOptions> parseCastOptions(int argc, char **argv) {
    CastOptions o;
    CLI::App app("mvcl-bench cast: one primary ray per pixel centre, hits and the sum of their distances, "
                 "for checking against another tracer.",
                 "mvcl-bench cast");
    app.formatter(std::make_shared<cli::UsageFormatter>(kCastUsage));
    app.set_help_flag("-h,--help", "this text");
    app.add_option("model", o.model, "model file or builtin:NAME (default the 2CylinderEngine); triangles only")
        ->option_text(" ");
    app.add_option_function<std::string>(
           "--camera", [&](const std::string &text) { o.camera = CastCamera::parse(text); },
           "world-space eye, target, up and vertical field of view in degrees (default: a three-quarter view)")
        ->type_name("EYE,TARGET,UP,FOVY");
    cli::addImageSizeOption(app, o.width, o.height, "one ray per pixel (default 1024x1024)");
    app.add_option("--threads", o.threads, "0 = all cores (default 0)")->type_name("N")->check(cli::wholeNumberIn(0, 1024));
    app.add_option("--repeat", o.repeat, "best of R runs (default 3)")->type_name("R")->check(cli::wholeNumberIn(1, 1000));
    app.add_flag("--peer", o.withPeer, "also cast the same rays with Embree's rtcIntersect1");
    if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::fputs(app.help().c_str(), stdout);
        return std::nullopt;
    }
    if (o.threads <= 0) o.threads = workerThreadCount();
    return o;
}

/// The view mvcl-bench's own measurements use, in world coordinates.
CastCamera threeQuarterView(const Scene &scene) {
    const Bounds3f b = scene.bounds();
    const glm::dvec3 center = glm::dvec3(b.center()) + scene.worldOrigin;
    const double radius = std::max(1e-6, 0.5 * double(glm::length(b.extent())));
    CastCamera c;
    c.verticalFovDegrees = 40.0;
    const double distance = radius / std::sin(0.5 * c.verticalFovDegrees * std::numbers::pi / 180.0);
    c.eye = center + distance * glm::normalize(glm::dvec3(0.6, 0.45, 0.75));
    c.target = center;
    return c;
}

/// Hit distances per ray, +∞ for a miss.
struct CastResult {
    std::vector<float> t;
    double seconds = 0.0;

    size_t hits() const {
        size_t n = 0;
        for (const float v : t) n += std::isfinite(v);
        return n;
    }
    /// float t summed into a double in pixel order.
    double sumOfDistances() const {
        double sum = 0.0;
        for (const float v : t)
            if (std::isfinite(v)) sum += double(v);
        return sum;
    }
};

void print(const char *prefix, const CastResult &r) {
    std::printf("%shits %zu\n", prefix, r.hits());
    std::printf("%ssum_t %.17g\n", prefix, r.sumOfDistances());
    std::printf("%sMrays/s %.3f\n", prefix, double(r.t.size()) / r.seconds * 1e-6);
}

} // namespace

int runCastBench(int argc, char **argv) {
    std::optional<CastOptions> options;
    try {
        options = parseCastOptions(argc, argv);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 2;
    }
    if (!options) return 0;
    const CastOptions &o = *options;
    try {
        const Scene scene = loadMeshes(o.model);
        const CastCamera camera = o.camera ? *o.camera : threeQuarterView(scene);
        const std::vector<Ray> rays = castRays(camera, o.width, o.height, scene.worldOrigin);
        std::printf("model   %s: %zu meshes, %zu triangles; scene space = world - (%.17g, %.17g, %.17g)\n",
                    o.model.c_str(), scene.meshes.size(), scene.triangleCount(), scene.worldOrigin.x,
                    scene.worldOrigin.y, scene.worldOrigin.z);
        std::printf("camera  %s\n", camera.text().c_str());
        std::printf("rays    %dx%d, one per pixel centre, row 0 at the top; %d threads, best of %d\n", o.width,
                    o.height, o.threads, o.repeat);

        TracerSettings settings;
        settings.buildThreads = o.threads;
        const Tracer tracer(scene, settings);
        const RayQuery query;
        CastResult ours;
        ours.t.assign(rays.size(), INFINITY);
        ours.seconds = bestSeconds(o.repeat, [&] {
            parallelRays(int(rays.size()), o.threads, [&](int i) {
                Hit hit;
                ours.t[size_t(i)] = tracer.closestHit(rays[size_t(i)], query, hit) ? hit.t : INFINITY;
            });
        });
        print("", ours);

        if (!o.withPeer) return 0;
#ifdef MVCL_HAVE_EMBREE
        RTCDevice device = rtcNewDevice(("threads=" + std::to_string(o.threads)).c_str());
        RTCScene peerScene = buildEmbree(device, scene);
        CastResult peer;
        peer.t.assign(rays.size(), INFINITY);
        peer.seconds = bestSeconds(o.repeat, [&] {
            parallelRays(int(rays.size()), o.threads, [&](int i) {
                RTCRayHit rh;
                intersectEmbree(peerScene, rays[size_t(i)], rh);
                peer.t[size_t(i)] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : INFINITY;
            });
        });
        rtcReleaseScene(peerScene);
        rtcReleaseDevice(device);
        print("embree ", peer);
        size_t sameHitOrMiss = 0, commonHits = 0, closeT = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            const bool a = std::isfinite(ours.t[i]), b = std::isfinite(peer.t[i]);
            sameHitOrMiss += a == b;
            if (a && b) {
                ++commonHits;
                closeT += std::fabs(ours.t[i] - peer.t[i]) <= 1e-4f * peer.t[i];
            }
        }
        std::printf("agree   hit/miss on %zu of %zu rays; |dt| <= 1e-4 t on %zu of %zu common hits; "
                    "speed ours/embree %.3f\n",
                    sameHitOrMiss, rays.size(), closeT, commonHits, peer.seconds / ours.seconds);
        return 0;
#else
        std::fprintf(stderr, "mvcl-bench: --peer needs Embree (libembree-dev); this build has none\n");
        return 2;
#endif
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 1;
    }
}

} // namespace mvcl::bench
