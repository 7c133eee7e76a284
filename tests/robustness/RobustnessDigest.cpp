// mvcl-robustness-digest: runs robustness cases 1–3 (watertight spheres), 14 (re-intersection),
// 17 (layer-gap sweep) and 28 (nested layers a hair apart) with fixed seeds and prints one line per case: the counts and a 64-bit
// hash of every hit (t bits, layer, geometry, primitive). Builds that compute the same hits print
// the same lines, so `diff` of two builds' output shows whether a compiler, an optimisation level
// or an FP flag changed any intersection result (catalogue case 27).
//
// Exit status: 0 if every case passed (no leak, no self-hit, every required layer-gap cell
// passed, no nested-layer cell showing the inner layer), 1 otherwise, 2 on a usage error.

#include "NestedLayerCases.h"
#include "RobustnessCases.h"

#include <mvcl/core/WorkerPool.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace mvcl::robustness;

namespace {

void usage() {
    std::fprintf(stderr,
                 "usage: mvcl-robustness-digest [--rays N] [--triangles N] [--spawned N] [--threads N]\n"
                 "  --rays N       rays per watertight case (default 200000; the tests use 1000000)\n"
                 "  --triangles N  re-intersection triangles (default 1000)\n"
                 "  --spawned N    rays spawned per re-intersection hit (default 1000)\n"
                 "  --threads N    worker threads (default: all cores; the output does not depend on it)\n"
                 "  --case NAME    only watertight, reintersection, layer-gap or nested-layers (default: all)\n");
}

bool parseCount(const char *text, uint64_t &value) {
    char *end = nullptr;
    const unsigned long long v = std::strtoull(text, &end, 10);
    if (!end || *end != '\0' || v == 0) return false;
    value = v;
    return true;
}

} // namespace

int main(int argc, char **argv) {
    uint64_t rays = 200000, triangles = 1000, spawned = 1000;
    uint64_t threads = uint64_t(mvcl::workerThreadCount());
    std::string only;
    for (int i = 1; i < argc; i += 2) { // options come as "--name value" pairs
        if (!std::strcmp(argv[i], "--case") && i + 1 < argc) {
            only = argv[i + 1];
            if (only != "watertight" && only != "reintersection" && only != "layer-gap" && only != "nested-layers") {
                usage();
                return 2;
            }
            continue;
        }
        uint64_t *target = nullptr;
        if (!std::strcmp(argv[i], "--rays")) target = &rays;
        else if (!std::strcmp(argv[i], "--triangles")) target = &triangles;
        else if (!std::strcmp(argv[i], "--spawned")) target = &spawned;
        else if (!std::strcmp(argv[i], "--threads")) target = &threads;
        if (!target || i + 1 >= argc || !parseCount(argv[i + 1], *target)) {
            usage();
            return 2;
        }
    }

    auto runs = [&](const char *name) { return only.empty() || only == name; };
    bool allPassed = true;
    for (const WatertightConfig &config :
         runs("watertight") ? standardWatertightConfigs(rays) : std::vector<WatertightConfig>{}) {
        const CaseCounts c = runWatertightCase(config, int(threads));
        allPassed &= c.failures == 0;
        std::printf("watertight %-34s rays=%" PRIu64 " leaks=%" PRIu64 " dups=%" PRIu64 " hash=%016" PRIx64 "\n",
                    config.name.c_str(), c.rays, c.failures, c.duplicates, c.hash);
    }
    if (runs("reintersection")) {
        const CaseCounts c = runReintersectionCase(uint32_t(triangles), uint32_t(spawned), 14, int(threads));
        allPassed &= c.failures == 0;
        std::printf("reintersection triangles=%" PRIu64 " spawned=%" PRIu64 " selfhits=%" PRIu64 " hash=%016" PRIx64 "\n",
                    triangles, c.rays, c.failures, c.hash);
    }
    for (const double s : runs("layer-gap") ? layerGapFractions() : std::vector<double>{})
        for (const double t : layerGapTranslations()) {
            const LayerGapCell cell = runLayerGapCell(s, t, 200, 17);
            if (cell.required && !cell.pass()) allPassed = false;
            std::printf("layer-gap s=%.0e T=%.0e rays=%" PRIu64 " primary=%" PRIu64 " refraction=%" PRIu64
                        " shadow=%" PRIu64 " reflection=%" PRIu64 " nonfinite=%" PRIu64
                        " required=%d pass=%d hash=%016" PRIx64 "\n",
                        s, t, cell.rays, cell.primaryWrong, cell.refractionWrong, cell.shadowWrong,
                        cell.reflectionWrong, cell.nonFinite, int(cell.required), int(cell.pass()), cell.hash);
        }
    // Case 28 at 400 × 400 (where it was seen), then the pass map at 64 × 64 per cell.
    auto printNested = [&](const NestedLayerConfig &config) {
        const NestedLayerCounts c = runNestedLayerCell(config, int(threads));
        allPassed &= c.pass();
        std::printf("nested-layers %s model=%" PRIu64 " inner=%" PRIu64 " shadow=%" PRIu64 " reflection=%" PRIu64
                    " refraction=%" PRIu64 " nonfinite=%" PRIu64 " pass=%d hash=%016" PRIx64 "\n",
                    describe(config).c_str(), c.modelPixels, c.innerShowing, c.shadowAcne, c.reflectionAcne,
                    c.refractionNotInner, c.nonFinite, int(c.pass()), c.hash);
    };
    for (const double t : runs("nested-layers") ? std::vector<double>{0.0, 1e7} : std::vector<double>{})
        for (const double g : {0.0, 1e-7, 3e-7, 1e-6}) {
            NestedLayerConfig config;
            config.gap = g;
            config.translation = t;
            config.width = config.height = 400;
            printNested(config);
        }
    for (const NestedTessellation tessellation : {NestedTessellation::Equal, NestedTessellation::Different})
        for (const double g : runs("nested-layers") ? nestedLayerGaps() : std::vector<double>{})
            for (const double k : nestedLayerScales())
                for (const double t : nestedLayerTranslations()) {
                    NestedLayerConfig config;
                    config.gap = g;
                    config.scale = k;
                    config.translation = t;
                    config.tessellation = tessellation;
                    if (tessellation == NestedTessellation::Different)
                        config.contactTolerance = nestedLayerDifferentTolerance();
                    config.width = config.height = 64;
                    printNested(config);
                }
    std::printf("result %s\n", allPassed ? "pass" : "FAIL");
    return allPassed ? 0 : 1;
}
