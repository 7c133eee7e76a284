// mvcl-bench: our tracer side by side with Embree 3 on the same mesh, the same rays and the same
// thread count, in one run. Measures BVH build, primary rays (closestHit vs rtcIntersect1),
// shadow rays toward a point light (anyHit vs rtcOccluded1) and incoherent diffuse-bounce rays
// (random hemisphere directions from the primary hits; closestHit vs rtcIntersect1), and checks
// that the hits agree. Then the same primary and shadow rays in 4×4 packets (closestHits and
// anyHits vs rtcIntersect16 and rtcOccluded16, PacketBench.cpp).
//
//   mvcl-bench [model.glb | builtin:<name>] [--size WxH] [--threads N] [--repeat R]
//              [--embree-config OPTIONS]   (extra rtcNewDevice options, e.g. tri_accel=bvh4.triangle4)
//   (exit 2 for bad arguments, 1 when the model does not load)
//   mvcl-bench convergence ...             (error against run time: ConvergenceBench.cpp)
//   mvcl-bench cast ...                    (identical primary rays for other tracers: CastBench.cpp)
//   mvcl-bench frame ...                   (a frame against its own rays unshaded: FrameBench.cpp)
//   mvcl-bench pov SCENE ...               (the scene as a POV-Ray 3.7 scene: PovBench.cpp)
//   mvcl-bench image-diff A B              (two images' difference in 8-bit levels: PovBench.cpp)

#include "CommandLineValues.h"
#include "AlternatingRuns.h"
#include "BenchSupport.h"
#include "CastBench.h"
#include "ConvergenceBench.h"
#include "FrameBench.h"
#include "LoadBench.h"
#include "ViewsBench.h"
#include "PovBench.h"

#include <mvcl/core/WorkerPool.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/RayOffset.h>
#include <mvcl/tracer/Tracer.h>

#include "EmbreePeer.h"
#include "PacketBench.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <exception>
#include <string>
#include <vector>

namespace {

#ifdef MVCL_HAVE_EMBREE
using mvcl::bench::buildEmbree;
using mvcl::bench::embreeMemoryMonitor;
using mvcl::bench::g_embreeBytes;
using mvcl::bench::g_embreePeak;
using mvcl::bench::intersectEmbree;
#endif

using mvcl::bench::alternate;
using mvcl::bench::bestSeconds;
using mvcl::bench::printRatio;
using mvcl::bench::Runs;
using mvcl::bench::loadMeshes;
using mvcl::bench::meshesOf;
using mvcl::bench::parallelRays;
using mvcl::bench::secondsSince;
using Clock = mvcl::bench::Clock;

struct Options {
    std::string model = "tests/data/models/2CylinderEngine/2CylinderEngine.glb";
    int width = 1024;
    int height = 1024;
    int threads = 0;
    int repeat = 3;
    std::string embreeConfig; ///< extra rtcNewDevice options, e.g. "tri_accel=bvh4.triangle4"
    /// --layers: load as mvcl-render does (layer inference), so that the queries reach several
    /// layers and pay for layer priority; by default the raw glTF (layers from extras only).
    bool inferLayers = false;
    mvcl::BvhQuality bvhQuality = mvcl::BvhQuality::Full;
};

/// Parses the command line; nullopt when help was asked for (and printed). Throws
/// mvcl::Error("command line", ...) for bad arguments.
std::optional<Options> parseOptions(int argc, char **argv) {
    Options o;
    CLI::App app("mvcl-bench: our tracer and Embree on the same mesh, rays and threads.", "mvcl-bench");
    app.formatter(std::make_shared<mvcl::cli::UsageFormatter>(
        "usage: mvcl-bench [model.glb | builtin:<name>] [--size WxH] [--threads N] [--repeat R]\n"
        "                  [--embree-config OPTIONS] [--layers]"));
    app.footer("Other modes (each with its own --help):\n"
               "  mvcl-bench convergence ...     error against run time of the sampling modes\n"
               "  mvcl-bench views ...           two views of one model: memory, lens drag, linked orbit\n"
               "  mvcl-bench cast ...            identical primary rays for checking another tracer\n"
               "  mvcl-bench frame ...           a frame's rays by kind and its rate against the same\n"
               "                                 rays traced again unshaded (the traversal bound)\n"
               "  mvcl-bench pov SCENE ...       the scene, camera, lights, materials and trace depth\n"
               "                                 mvcl-render uses, as a POV-Ray 3.7 scene, and the\n"
               "                                 mvcl-render camera options of the same view\n"
               "  mvcl-bench image-diff A B      two images' difference in 8-bit levels");
    app.set_help_flag("-h,--help", "this text");
    app.add_option("model", o.model, "model file or builtin:NAME (default the 2CylinderEngine)")->option_text(" ");
    mvcl::cli::addImageSizeOption(app, o.width, o.height, "primary rays, one per pixel of a WxH image (default 1024x1024)");
    app.add_option("--threads", o.threads, "threads for both tracers, 0 = all cores (default 0)")
        ->type_name("N")
        ->check(mvcl::cli::wholeNumberIn(0, 1024));
    app.add_option("--repeat", o.repeat, "best of R runs (default 3)")->type_name("R")->check(mvcl::cli::wholeNumberIn(1, 1000));
    app.add_option("--embree-config", o.embreeConfig, "extra rtcNewDevice options, e.g. tri_accel=bvh4.triangle4")
        ->type_name("OPTIONS");
    app.add_option("--bvh-quality", o.bvhQuality,
                   "full: our SAH build against Embree's medium quality (default); quick: our Morton\n"
                   "build against Embree's low quality (its Morton build)")
        ->type_name("full|quick")
        ->transform(CLI::CheckedTransformer(std::map<std::string, mvcl::BvhQuality>{{"full", mvcl::BvhQuality::Full},
                                                                                   {"quick", mvcl::BvhQuality::Quick}}));
    app.add_flag("--layers", o.inferLayers,
                 "load the model as mvcl-render does (layer rules none, containment inference), so that\n"
                 "closest-hit queries reach several layers and pay for layer priority");
    if (mvcl::cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::fputs(app.help().c_str(), stdout);
        return std::nullopt;
    }
    if (o.threads <= 0) o.threads = mvcl::workerThreadCount();
    return o;
}

struct Rays {
    std::vector<mvcl::Ray> rays;
    std::vector<float> tMax;
};

/// A pinhole camera framing the scene bounds from a three-quarter view.
Rays primaryRays(const mvcl::Scene &scene, int width, int height) {
    const mvcl::Bounds3f b = scene.bounds();
    const glm::vec3 center = b.center();
    const float radius = std::max(1e-6f, 0.5f * glm::length(b.extent()));
    const float fov = glm::radians(40.f);
    const float distance = radius / std::sin(0.5f * fov);
    const glm::vec3 eye = center + distance * glm::normalize(glm::vec3(0.6f, 0.45f, 0.75f));
    const glm::vec3 forward = glm::normalize(center - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.f, 1.f, 0.f)));
    const glm::vec3 up = glm::cross(right, forward);
    const float tanHalf = std::tan(0.5f * fov);
    const float aspect = float(width) / float(height);
    Rays r;
    r.rays.reserve(std::size_t(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float sx = (2.f * (float(x) + 0.5f) / float(width) - 1.f) * tanHalf * aspect;
            const float sy = (1.f - 2.f * (float(y) + 0.5f) / float(height)) * tanHalf;
            r.rays.push_back({eye, glm::normalize(forward + sx * right + sy * up)});
        }
    r.tMax.assign(r.rays.size(), std::numeric_limits<float>::infinity());
    return r;
}

double mrays(std::size_t n, double seconds) { return double(n) / seconds * 1e-6; }


void printRow(const char *what, double ours, double embree, const char *unit, bool higherIsBetter) {
    if (embree > 0.0)
        std::printf("%-22s ours %10.3f %-8s embree %10.3f %-8s ratio ours/embree %.3f%s\n", what,
                    ours, unit, embree, unit, ours / embree,
                    higherIsBetter ? "" : " (lower is better)");
    else
        std::printf("%-22s ours %10.3f %s\n", what, ours, unit);
}

} // namespace

int main(int argc, char **argv) {
    if (argc > 1 && std::string(argv[1]) == "convergence") return mvcl::bench::runConvergenceBench(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "cast") return mvcl::bench::runCastBench(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "frame") return mvcl::bench::runFrameBench(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "pov") return mvcl::bench::runPovExport(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "load") return mvcl::bench::runLoadBench(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "views") return mvcl::bench::runViewsBench(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "image-diff") return mvcl::bench::runImageDiff(argc - 1, argv + 1);
    std::optional<Options> options;
    try {
        options = parseOptions(argc, argv);
    } catch (const mvcl::Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 2;
    }
    if (!options) return 0;
    try {
        const Options &opt = *options;
        const auto loadStart = Clock::now();
        const mvcl::Scene scene = opt.inferLayers ? meshesOf(mvcl::loadScene(opt.model)) : loadMeshes(opt.model);
        uint32_t layers = 0;
        for (const mvcl::TriangleMesh &m : scene.meshes) layers |= 1u << std::clamp(m.layer, 0, 31);
        std::printf("model %s: %zu meshes, %zu triangles, %d layers, loaded in %.1f ms\n", opt.model.c_str(),
                    scene.meshes.size(), scene.triangleCount(), std::popcount(layers), secondsSince(loadStart) * 1e3);
        std::printf("%dx%d primary rays, %d threads, best of %d runs, on %s\n", opt.width, opt.height,
                    opt.threads, opt.repeat, mvcl::bench::cpuModelName().c_str());

        // --- Build ---
        mvcl::TracerSettings settings;
        settings.buildThreads = opt.threads;
        settings.bvhQuality = opt.bvhQuality;
        std::unique_ptr<mvcl::Tracer> tracer;
        const double oursBuild = bestSeconds(opt.repeat, [&] {
            tracer.reset();
            tracer = std::make_unique<mvcl::Tracer>(scene, settings);
        });
        const mvcl::TracerBuildStats &st = tracer->buildStats();

        double embreeBuild = 0.0;
#ifdef MVCL_HAVE_EMBREE
        std::string config = "threads=" + std::to_string(opt.threads);
        if (!opt.embreeConfig.empty()) config += "," + opt.embreeConfig;
        RTCDevice device = rtcNewDevice(config.c_str());
        rtcSetDeviceMemoryMonitorFunction(device, embreeMemoryMonitor, nullptr);
        RTCScene escene = nullptr;
        long long embreeBytes = 0;
        embreeBuild = bestSeconds(opt.repeat, [&] {
            if (escene) rtcReleaseScene(escene);
            const long long before = g_embreeBytes.load();
            escene = buildEmbree(device, scene,
                                 opt.bvhQuality == mvcl::BvhQuality::Quick ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
            embreeBytes = g_embreeBytes.load() - before;
        });
#endif
        std::printf("\nours: %zu triangles, %zu nodes, %zu leaves, depth %d\n", st.triangles,
                    st.nodes, st.leaves, st.maxDepth);
        printRow("build", oursBuild * 1e3, embreeBuild * 1e3, "ms", false);

        // --- Primary rays ---
        const Rays primary = primaryRays(scene, opt.width, opt.height);
        const int n = int(primary.rays.size());
        std::vector<mvcl::Hit> hits(n);
        std::vector<char> found(n);
        const mvcl::RayQuery primaryQuery; // made once, as a renderer would per frame
        bool withPeer = false;
#ifdef MVCL_HAVE_EMBREE
        withPeer = true;
        std::vector<RTCRayHit> eh(n);
#endif
        // Each pair of measurements alternates the two tracers run by run (AlternatingRuns.h).
        Runs oursPrimary, embreePrimary;
        alternate(
            opt.repeat, withPeer,
            [&] {
                parallelRays(n, opt.threads, [&](int i) {
                    found[i] = tracer->closestHit(primary.rays[i], primaryQuery, hits[i]);
                });
            },
            [&] {
#ifdef MVCL_HAVE_EMBREE
                parallelRays(n, opt.threads, [&](int i) { intersectEmbree(escene, primary.rays[i], eh[i]); });
#endif
            },
            oursPrimary, embreePrimary);

        // Shadow rays from our primary hits toward a point light above and behind the camera.
        const mvcl::Bounds3f b = scene.bounds();
        const glm::vec3 light =
            b.center() + glm::length(b.extent()) * glm::vec3(0.4f, 1.2f, 0.6f);
        std::vector<mvcl::Ray> shadow;
        std::vector<int> shadowPixel; // for the packet rows: the 4×4 tile of each shadow ray
        shadow.reserve(n);
        for (int i = 0; i < n; ++i) {
            if (!found[i]) continue;
            const mvcl::SurfaceInteraction si = tracer->interaction(primary.rays[i], hits[i]);
            const glm::vec3 o =
                mvcl::offsetRayOrigin(si.position, si.positionError, si.geometricNormal,
                                      light - si.position);
            shadow.push_back({o, light - o}); // t in (0, 1) reaches the light
            shadowPixel.push_back(i);
        }
        const int ns = int(shadow.size());

        // Diffuse bounce rays: a uniform random direction in the hemisphere of the geometric
        // normal facing the camera, from the same offset origins (seeded per ray: reproducible).
        std::vector<mvcl::Ray> bounce;
        bounce.reserve(n);
        for (int i = 0; i < n; ++i) {
            if (!found[i]) continue;
            const mvcl::SurfaceInteraction si = tracer->interaction(primary.rays[i], hits[i]);
            glm::vec3 normal = si.geometricNormal;
            if (glm::dot(normal, primary.rays[i].direction) > 0.f) normal = -normal;
            std::mt19937 rng{uint32_t(i)};
            std::normal_distribution<float> gauss(0.f, 1.f);
            glm::vec3 dir;
            do {
                dir = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
            } while (glm::length(dir) < 1e-3f);
            dir = glm::normalize(dir);
            if (glm::dot(dir, normal) < 0.f) dir = -dir;
            bounce.push_back({mvcl::offsetRayOrigin(si.position, si.positionError, normal, dir), dir});
        }
        const int nb = int(bounce.size());
        mvcl::RayQuery shadowQuery;
        shadowQuery.tMax = 1.f - 1e-4f;
        std::vector<char> occluded(ns);
#ifdef MVCL_HAVE_EMBREE
        std::vector<char> eOccluded(ns);
#endif
        Runs oursShadow, embreeShadow;
        alternate(
            opt.repeat, withPeer,
            [&] {
                parallelRays(ns, opt.threads, [&](int i) { occluded[i] = tracer->anyHit(shadow[i], shadowQuery); });
            },
            [&] {
#ifdef MVCL_HAVE_EMBREE
                parallelRays(ns, opt.threads, [&](int i) {
                    RTCIntersectContext ctx;
                    rtcInitIntersectContext(&ctx);
                    RTCRay ray;
                    const mvcl::Ray &r = shadow[i];
                    ray.org_x = r.origin.x, ray.org_y = r.origin.y, ray.org_z = r.origin.z;
                    ray.dir_x = r.direction.x, ray.dir_y = r.direction.y, ray.dir_z = r.direction.z;
                    ray.tnear = 0.f;
                    ray.tfar = shadowQuery.tMax;
                    ray.mask = ~0u;
                    ray.flags = 0;
                    ray.time = 0.f;
                    rtcOccluded1(escene, &ctx, &ray);
                    eOccluded[i] = ray.tfar < 0.f; // Embree sets tfar = −inf when occluded
                });
#endif
            },
            oursShadow, embreeShadow);

        std::vector<mvcl::Hit> bounceHits(nb);
        std::vector<char> bounceFound(nb);
#ifdef MVCL_HAVE_EMBREE
        std::vector<RTCRayHit> ebh(nb);
#endif
        Runs oursBounce, embreeBounce;
        alternate(
            opt.repeat, withPeer,
            [&] {
                parallelRays(nb, opt.threads, [&](int i) {
                    bounceFound[i] = tracer->closestHit(bounce[i], primaryQuery, bounceHits[i]);
                });
            },
            [&] {
#ifdef MVCL_HAVE_EMBREE
                parallelRays(nb, opt.threads, [&](int i) { intersectEmbree(escene, bounce[i], ebh[i]); });
#endif
            },
            oursBounce, embreeBounce);
        std::printf("\n");
        // The best runs in the row, then the medians and the spread of the back-to-back pairs.
        auto rayRow = [&](const char *what, std::size_t count, const Runs &ours, const Runs &peer) {
            printRow(what, mrays(count, ours.best()), withPeer ? mrays(count, peer.best()) : 0.0, "Mrays/s", true);
            if (withPeer) printRatio(ours, peer);
        };
        rayRow("primary (closestHit)", std::size_t(n), oursPrimary, embreePrimary);
        rayRow("shadow (anyHit)", std::size_t(ns), oursShadow, embreeShadow);
        rayRow("diffuse (closestHit)", std::size_t(nb), oursBounce, embreeBounce);
        std::printf("%-22s ours %10.2f MB", "memory", double(st.memoryBytes) / (1 << 20));
#ifdef MVCL_HAVE_EMBREE
        std::printf("   embree %10.2f MB (scene allocations)", double(embreeBytes) / (1 << 20));
#endif
        std::printf("\nprimary hits: %d of %d rays; shadow rays: %d, occluded: %ld; diffuse rays: "
                    "%d, hits: %ld\n",
                    int(std::count(found.begin(), found.end(), 1)), n, ns,
                    long(std::count(occluded.begin(), occluded.end(), 1)), nb,
                    long(std::count(bounceFound.begin(), bounceFound.end(), 1)));

#ifdef MVCL_HAVE_EMBREE
        // Agreement: same hit/miss, same mesh and triangle, t within a relative 1e-4.
        int sameHitMiss = 0, samePrim = 0, closeT = 0, bothHit = 0;
        for (int i = 0; i < n; ++i) {
            const bool eHit = eh[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
            if (eHit != bool(found[i])) continue;
            ++sameHitMiss;
            if (!eHit) continue;
            ++bothHit;
            if (eh[i].hit.geomID == hits[i].geometry && eh[i].hit.primID == hits[i].primitive)
                ++samePrim;
            if (std::fabs(eh[i].ray.tfar - hits[i].t) <= 1e-4f * std::max(1.f, hits[i].t)) ++closeT;
        }
        int sameOcclusion = 0;
        for (int i = 0; i < ns; ++i) sameOcclusion += eOccluded[i] == occluded[i];
        int sameBounce = 0;
        for (int i = 0; i < nb; ++i)
            sameBounce += (ebh[i].hit.geomID != RTC_INVALID_GEOMETRY_ID) == bool(bounceFound[i]);
        std::printf("agreement with embree: hit/miss %.4f%%, same mesh+triangle %.4f%% of common "
                    "hits, |dt| <= 1e-4 t %.4f%%, shadow %.4f%%, diffuse hit/miss %.4f%%\n",
                    100.0 * sameHitMiss / n, bothHit ? 100.0 * samePrim / bothHit : 100.0,
                    bothHit ? 100.0 * closeT / bothHit : 100.0, ns ? 100.0 * sameOcclusion / ns : 100.0,
                    nb ? 100.0 * sameBounce / nb : 100.0);
#endif
        mvcl::bench::PacketBenchInput packets;
        packets.tracer = tracer.get();
#ifdef MVCL_HAVE_EMBREE
        packets.embree = escene;
#endif
        packets.primary = &primary.rays;
        packets.width = opt.width;
        packets.height = opt.height;
        packets.primaryQuery = primaryQuery;
        packets.shadow = &shadow;
        packets.shadowPixel = &shadowPixel;
        packets.shadowQuery = shadowQuery;
        packets.threads = opt.threads;
        packets.repeat = opt.repeat;
        const bool packetsAgree = mvcl::bench::runPacketComparison(packets);
#ifdef MVCL_HAVE_EMBREE
        rtcReleaseScene(escene);
        rtcReleaseDevice(device);
#endif
        return packetsAgree ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return 1;
    }
}
