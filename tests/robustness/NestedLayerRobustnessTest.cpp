// Catalogue case 28: nested layers a hair apart (NestedLayerCases.h). The outer layer wins
// wherever its hit lies within the error bound of the nearest hit (equal tessellations, down to a
// gap of zero) or within the scene's contact tolerance (different tessellations).

#include "NestedLayerCases.h"

#include <mvcl/core/WorkerPool.h>
#include <mvcl/tracer/LayerContactProbe.h>
#include <mvcl/tracer/Tracer.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace mvcl::robustness {
namespace {

void measured(const std::string &line) { std::printf("[ measured ] %s\n", line.c_str()); }

/// The view where the fault was seen: two nested spheres of equal tessellation at 400 × 400, one ray per pixel,
/// at the origin and at 10⁷ sizes from it. Every pixel of the model shows the outer layer.
TEST(RobustnessNestedLayers, EqualTessellationsNeverShowTheInnerLayerAt400x400) {
    for (const double translation : {0.0, 1e7})
        for (const double gap : {0.0, 1e-7, 3e-7, 1e-6, 1e-5}) {
            NestedLayerConfig config;
            config.gap = gap;
            config.translation = translation;
            config.width = config.height = 400;
            const NestedLayerCounts c = runNestedLayerCell(config, workerThreadCount());
            measured(describe(config) + ": model pixels=" + std::to_string(c.modelPixels) +
                     " inner showing=" + std::to_string(c.innerShowing) + " shadow acne=" +
                     std::to_string(c.shadowAcne) + " reflection acne=" + std::to_string(c.reflectionAcne));
            EXPECT_GT(c.modelPixels, 30000u) << describe(config);
            EXPECT_EQ(c.innerShowing, 0u) << describe(config);
            EXPECT_EQ(c.shadowAcne, 0u) << describe(config);
            EXPECT_EQ(c.reflectionAcne, 0u) << describe(config);
            EXPECT_EQ(c.nonFinite, 0u) << describe(config);
        }
}

/// Gap × scale × translation for one tessellation, as a text table (rows: gap; columns: scale
/// and translation); returns the number of failing cells.
int runPassMap(NestedTessellation tessellation, double tolerance, std::string &map, uint64_t &rays) {
    std::ostringstream os;
    char buf[64];
    os << "      g \\ k,T";
    for (const double k : nestedLayerScales())
        for (const double t : nestedLayerTranslations()) {
            std::snprintf(buf, sizeof buf, " %5.0e,%-4.0e", k, t);
            os << buf;
        }
    os << '\n';
    int failures = 0;
    for (const double g : nestedLayerGaps()) {
        std::snprintf(buf, sizeof buf, "%12.0e", g);
        os << buf;
        for (const double k : nestedLayerScales())
            for (const double t : nestedLayerTranslations()) {
                NestedLayerConfig config;
                config.gap = g;
                config.scale = k;
                config.translation = t;
                config.tessellation = tessellation;
                config.contactTolerance = tolerance;
                const NestedLayerCounts c = runNestedLayerCell(config, workerThreadCount());
                rays += c.modelPixels;
                const bool ok = c.pass() && c.refractionNotInner == 0 && c.modelPixels > 0;
                if (!ok) {
                    ++failures;
                    std::printf("  fail %s: inner=%llu shadow=%llu reflection=%llu refraction=%llu nonfinite=%llu\n",
                                describe(config).c_str(), (unsigned long long)c.innerShowing,
                                (unsigned long long)c.shadowAcne, (unsigned long long)c.reflectionAcne,
                                (unsigned long long)c.refractionNotInner, (unsigned long long)c.nonFinite);
                }
                if (ok) std::snprintf(buf, sizeof buf, " %11s", "ok");
                else std::snprintf(buf, sizeof buf, " %11llu", (unsigned long long)c.innerShowing);
                os << buf;
            }
        os << '\n';
    }
    map = os.str();
    return failures;
}

/// The pass map: gaps 0 … 1e-3, scales 1e-7 … 1e7, translations 0 … 10⁷ model sizes, 100 × 100
/// primary rays per cell with their shadow, reflection and (where the gap is resolvable)
/// refraction rays. Every cell passes.
TEST(RobustnessNestedLayers, PassMapEqualTessellations) {
    std::string map;
    uint64_t rays = 0;
    const int failures = runPassMap(NestedTessellation::Equal, 0.0, map, rays);
    std::printf("nested-layer pass map, equal tessellations (ok = pass, else inner pixels showing):\n%s",
                map.c_str());
    measured("nested layers, equal tessellations: model pixels=" + std::to_string(rays) +
             " failing cells=" + std::to_string(failures));
    EXPECT_EQ(failures, 0);
}

/// Different tessellations: the outer sphere's facets cut inside the inner sphere's vertices by up
/// to their sagitta, far beyond float rounding. Without a tolerance the inner layer shows (that is
/// what the tolerance is for); with the one --info suggests (probeLayerContacts), every cell passes.
TEST(RobustnessNestedLayers, PassMapDifferentTessellationsUnderTheContactTolerance) {
    NestedLayerConfig config;
    config.tessellation = NestedTessellation::Different;
    const NestedLayerCounts without = runNestedLayerCell(config, workerThreadCount());
    measured("different tessellations, g = 0, no tolerance: inner showing=" + std::to_string(without.innerShowing) +
             " of " + std::to_string(without.modelPixels));
    EXPECT_GT(without.innerShowing, 0u);

    const Scene scene = makeNestedSpheres(config);
    const Tracer tracer(scene);
    const LayerContactReport report = probeLayerContacts(tracer);
    ASSERT_EQ(report.pairs.size(), 1u);
    EXPECT_EQ(report.pairs[0].outerLayer, 0);
    EXPECT_EQ(report.pairs[0].innerLayer, 1);
    ASSERT_TRUE(report.suggested.isEnabled());
    // Near the outer facets' largest sagitta (nestedLayerDifferentTolerance() is 1.5 × it).
    const double sagitta = nestedLayerDifferentTolerance() / 1.5;
    measured("--info suggests " + report.suggested.toString() + " (relative); the outer facets' largest sagitta is " +
             std::to_string(sagitta));
    EXPECT_GE(report.suggested.distance, 0.5 * sagitta);
    EXPECT_LE(report.suggested.distance, 2.0 * sagitta);

    // The map under the suggested value.
    std::string map;
    uint64_t rays = 0;
    const int failures = runPassMap(NestedTessellation::Different, report.suggested.distance, map, rays);
    std::printf("nested-layer pass map, different tessellations under the contact tolerance:\n%s", map.c_str());
    measured("nested layers, different tessellations: model pixels=" + std::to_string(rays) +
             " failing cells=" + std::to_string(failures));
    EXPECT_EQ(failures, 0);
}

/// Equal tessellations: --info finds the touching pair and suggests no tolerance.
TEST(RobustnessNestedLayers, ProbeFindsEqualTessellationsNeedNoTolerance) {
    for (const double g : {0.0, 1e-7}) {
        NestedLayerConfig config;
        config.gap = g;
        const Scene scene = makeNestedSpheres(config);
        const Tracer tracer(scene);
        const LayerContactReport report = probeLayerContacts(tracer);
        ASSERT_EQ(report.pairs.size(), 1u) << g;
        EXPECT_FALSE(report.suggested.isEnabled()) << g << ": " << report.suggested.toString();
    }
    // Far apart (g = 1e-2, beyond the probe's reach of 1e-3 of the scene's size): no pair at all.
    NestedLayerConfig apart;
    apart.gap = 1e-2;
    const Scene scene = makeNestedSpheres(apart);
    const Tracer tracer(scene);
    EXPECT_TRUE(probeLayerContacts(tracer).pairs.empty());
}

} // namespace
} // namespace mvcl::robustness
