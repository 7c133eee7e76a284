// The depth histogram of a layer lens: surface crossings along the rays under the lens, per
// layer, and suggestions for the lens's distance that lie in the gaps between surfaces. The
// expected gaps come from the scenes' analytic geometry (boxes, spheres, the floor), traced in
// double through every pixel the region covers.

#include <mvcl/view/DepthHistogram.h>

#include "PluginLens.h"

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Picking.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

using namespace mvcl;
using test::pluginLens;

namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 240;

struct Interval {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    void add(double t) {
        lo = std::min(lo, t);
        hi = std::max(hi, t);
    }
    bool contains(double t) const { return t > lo && t < hi; }
};

struct DRay {
    glm::dvec3 o, d;
};

/// Entry and exit of the box [c − h, c + h], if the ray crosses it in front of the eye.
std::optional<std::pair<double, double>> boxCrossings(const DRay &r, const glm::dvec3 &c, double h) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const double n = (c[a] - h - r.o[a]) / r.d[a], f = (c[a] + h - r.o[a]) / r.d[a];
        t0 = std::max(t0, std::min(n, f));
        t1 = std::min(t1, std::max(n, f));
    }
    if (!(t0 < t1)) return std::nullopt;
    return std::make_pair(t0, t1);
}

std::optional<std::pair<double, double>> sphereCrossings(const DRay &r, const glm::dvec3 &c, double radius) {
    const glm::dvec3 oc = r.o - c;
    const double b = glm::dot(oc, r.d), disc = b * b - (glm::dot(oc, oc) - radius * radius);
    if (disc <= 0.0) return std::nullopt;
    return std::make_pair(-b - std::sqrt(disc), -b + std::sqrt(disc));
}

/// Named surfaces and the distances at which a ray crosses them.
using SurfaceCrossings = std::function<std::map<std::string, double>(const DRay &)>;

/// For every pixel the region covers: the range of t over which each surface is crossed.
std::map<std::string, Interval> surfaceClusters(const Camera &camera, const LensRegion &region,
                                                const SurfaceCrossings &crossings) {
    std::map<std::string, Interval> clusters;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            if (!(region.coverage({float(x) + 0.5f, float(y) + 0.5f}, kWidth, kHeight) > 0.f)) continue;
            const Ray ray = camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, kWidth, kHeight);
            for (const auto &[name, t] : crossings({glm::dvec3(ray.origin), glm::dvec3(ray.direction)}))
                clusters[name].add(t);
        }
    return clusters;
}

/// The open intervals of t that no surface's cluster touches, between the first and last.
std::vector<Interval> gapsBetween(const std::map<std::string, Interval> &clusters) {
    std::vector<Interval> sorted;
    for (const auto &[name, interval] : clusters) sorted.push_back(interval);
    std::sort(sorted.begin(), sorted.end(), [](const Interval &a, const Interval &b) { return a.lo < b.lo; });
    std::vector<Interval> gaps;
    double reach = sorted.front().hi;
    for (std::size_t i = 1; i < sorted.size(); ++i) {
        if (sorted[i].lo > reach) gaps.push_back({reach, sorted[i].lo});
        reach = std::max(reach, sorted[i].hi);
    }
    return gaps;
}

/// Index of the gap that holds t, -1 if none.
int gapHolding(const std::vector<Interval> &gaps, double t) {
    for (std::size_t i = 0; i < gaps.size(); ++i)
        if (gaps[i].contains(t)) return int(i);
    return -1;
}

/// Every suggestion lies in a gap; every gap at least two bins wide (so one bin is surely empty)
/// holds a suggestion.
void expectSuggestionsInGaps(const DepthHistogram &h, const std::vector<Interval> &gaps) {
    ASSERT_FALSE(h.suggestions.empty());
    for (const DepthSuggestion &s : h.suggestions) {
        EXPECT_GE(gapHolding(gaps, s.distance), 0) << "d = " << s.distance << " lies on a surface cluster";
        EXPECT_LT(s.gapBegin, s.distance);
        EXPECT_GT(s.gapEnd, s.distance);
        EXPECT_GT(s.raysSeparated, 0u);
    }
    for (const Interval &gap : gaps) {
        if (gap.hi - gap.lo < 2.0 * double(h.binWidth())) continue;
        EXPECT_TRUE(std::any_of(h.suggestions.begin(), h.suggestions.end(),
                                [&](const DepthSuggestion &s) { return gap.contains(s.distance); }))
            << "no suggestion in the gap (" << gap.lo << ", " << gap.hi << ")";
    }
}

/// Counts per layer add up to the totals.
void expectConsistentBins(const DepthHistogram &h) {
    uint64_t total = 0;
    for (uint32_t c : h.counts) total += c;
    EXPECT_EQ(total, h.crossings);
    uint64_t perLayer = 0;
    for (const LayerDepths &layer : h.layers) {
        ASSERT_EQ(layer.counts.size(), h.counts.size());
        uint64_t sum = 0;
        for (uint32_t c : layer.counts) sum += c;
        EXPECT_EQ(sum, layer.crossings);
        EXPECT_LE(layer.nearest, layer.farthest);
        EXPECT_GE(layer.nearest, h.tNear);
        EXPECT_LE(layer.farthest, h.tFar);
        perLayer += sum;
    }
    EXPECT_EQ(perLayer, h.crossings);
}

DepthHistogramRequest regionRequest(const Camera &camera, const LensRegion &region, const RayPolicy &base = {}) {
    DepthHistogramRequest request;
    request.camera = camera;
    request.width = kWidth;
    request.height = kHeight;
    request.region = region;
    request.base = base;
    return request;
}

/// Pixels whose centre lies inside the region beyond its feather (coverage 1).
template <class Visit> void forEachInnerPixel(const LensRegion &region, Visit &&visit) {
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (region.coverage({float(x) + 0.5f, float(y) + 0.5f}, kWidth, kHeight) >= 1.f) visit(x, y);
}

// The surfaces of the two built-in scenes, as the tracer sees them (the cubes are meshes with
// flat faces, so the slab test is exact).
std::map<std::string, double> cubeInCubeCrossings(const DRay &r) {
    std::map<std::string, double> out;
    if (const auto outer = boxCrossings(r, {0.0, 1.0, 0.0}, 1.0)) {
        out["outer front"] = outer->first;
        out["outer back"] = outer->second;
    }
    if (const auto inner = boxCrossings(r, {0.0, 1.0, 0.0}, 0.45)) {
        out["inner front"] = inner->first;
        out["inner back"] = inner->second;
    }
    if (r.d.y < 0.0) out["floor"] = -r.o.y / r.d.y;
    EXPECT_FALSE(sphereCrossings(r, {-2.3, 0.7, 0.6}, 0.7) || sphereCrossings(r, {1.9, 0.6, 1.4}, 0.6))
        << "the region should see only the cubes and the floor";
    return out;
}

std::map<std::string, double> onionCrossings(const DRay &r) {
    std::map<std::string, double> out;
    for (int layer = 0; layer < 4; ++layer)
        if (const auto s = sphereCrossings(r, {0.0, 1.0, 0.0}, 1.0 - 0.22 * layer)) {
            out["front " + std::to_string(layer)] = s->first;
            out["back " + std::to_string(layer)] = s->second;
        }
    if (r.d.y < 0.0) out["floor"] = -r.o.y / r.d.y;
    return out;
}

} // namespace

TEST(DepthHistogram, CubeInCubeSuggestionsFallInTheGapsAndRevealTheInnerCube) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    const LensRegion region = LensRegion::ellipse({0.5f, 0.5f}, {0.15f, 0.2f});

    const DepthHistogram h = computeDepthHistogram(tracer, regionRequest(camera, region));
    ASSERT_FALSE(h.isEmpty());
    EXPECT_FALSE(h.cancelled);
    EXPECT_EQ(h.raysHit, h.raysSampled);
    EXPECT_EQ(h.raysTruncated, 0u);
    EXPECT_GE(h.pixelStep, 1);
    expectConsistentBins(h);
    ASSERT_NE(h.layer(0), nullptr);
    ASSERT_NE(h.layer(1), nullptr);
    EXPECT_EQ(h.layer(1)->name, "inner cube");
    EXPECT_EQ(h.layer(0)->firstHits, h.raysHit) << "every ray meets the outer cube first";

    const std::map<std::string, Interval> clusters = surfaceClusters(camera, region, cubeInCubeCrossings);
    // Inner-cube crossings lie where the geometry puts them.
    EXPECT_GE(h.layer(1)->nearest, clusters.at("inner front").lo - 1e-4);
    EXPECT_LE(h.layer(1)->farthest, clusters.at("inner back").hi + 1e-4);
    const std::vector<Interval> gaps = gapsBetween(clusters);
    ASSERT_FALSE(gaps.empty());
    ASSERT_EQ(gaps.front().lo, clusters.at("outer front").hi) << "the first gap is in front of the inner cube";
    expectSuggestionsInGaps(h, gaps);

    // The best suggestion peels the outer cube: a lens showing every layer beyond it shows the inner one.
    const DepthSuggestion &best = h.suggestions.front();
    EXPECT_EQ(gapHolding(gaps, best.distance), 0);
    EXPECT_EQ(best.layerBefore, 0);
    EXPECT_EQ(best.layerAfter, 1);
    const std::shared_ptr<Lens> lens = pluginLens("layer", region, {{"layers", "all"}});
    LensStack stack;
    stack.add(lens);
    EXPECT_EQ(pick(tracer, camera, stack.compose({}, kWidth, kHeight), kWidth / 2, kHeight / 2).layer, 0);
    applyLensDistance(*lens, best.distance);
    const PolicyMap map = stack.compose({}, kWidth, kHeight);
    int revealed = 0;
    forEachInnerPixel(region, [&](int x, int y) {
        const Ray ray = camera.generateRay(float(x) + 0.5f, float(y) + 0.5f, kWidth, kHeight);
        if (!boxCrossings({glm::dvec3(ray.origin), glm::dvec3(ray.direction)}, {0.0, 1.0, 0.0}, 0.45)) return;
        const PickResult p = pick(tracer, camera, map, x, y);
        EXPECT_TRUE(p.hit && p.layer == 1 && p.objectName == "inner cube") << x << "," << y;
        ++revealed;
    });
    EXPECT_GT(revealed, 100);
}

TEST(DepthHistogram, OnionSuggestionsFallInTheGapsAndEachPeelsOneLayer) {
    const Scene scene = loadScene("builtin:onion");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    const LensRegion region = LensRegion::ellipse({0.5f, 0.47f}, {0.1f, 0.13f});

    const DepthHistogram h = computeDepthHistogram(tracer, regionRequest(camera, region));
    ASSERT_FALSE(h.isEmpty());
    expectConsistentBins(h);
    ASSERT_EQ(h.layers.size(), 4u);
    for (int layer = 0; layer < 4; ++layer) EXPECT_EQ(h.layers[std::size_t(layer)].layer, layer);

    const std::map<std::string, Interval> clusters = surfaceClusters(camera, region, onionCrossings);
    const std::vector<Interval> gaps = gapsBetween(clusters);
    expectSuggestionsInGaps(h, gaps);

    // Nearest first among equals: the first three suggestions peel skin, flesh and core.
    ASSERT_GE(h.suggestions.size(), 3u);
    for (int layer = 1; layer < 4; ++layer) {
        const DepthSuggestion &s = h.suggestions[std::size_t(layer - 1)];
        const std::string front = "front " + std::to_string(layer);
        EXPECT_GT(s.distance, clusters.at("front " + std::to_string(layer - 1)).hi);
        EXPECT_LT(s.distance, clusters.at(front).lo);
        EXPECT_EQ(s.layerAfter, layer);

        const std::shared_ptr<Lens> lens = pluginLens("layer", region, {{"layers", "all"}});
        applyLensDistance(*lens, s.distance);
        LensStack stack;
        stack.add(lens);
        const PolicyMap map = stack.compose({}, kWidth, kHeight);
        int peeled = 0;
        forEachInnerPixel(region, [&](int x, int y) {
            const PickResult p = pick(tracer, camera, map, x, y);
            EXPECT_TRUE(p.hit && p.layer == layer) << "d = " << s.distance << " at " << x << "," << y;
            ++peeled;
        });
        EXPECT_GT(peeled, 50);
    }
}

TEST(DepthHistogram, LensInAStackLeavesItsOwnConstraintsOutAndKeepsTheOthers) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    const LensRegion region = LensRegion::ellipse({0.5f, 0.5f}, {0.15f, 0.2f});

    // The lens hides layer 0 and everything nearer than 7.5; its histogram still shows them all.
    LensStack stack;
    stack.add(pluginLens("layer", region, {{"layers", "1-"}, {"distance", "7.5"}}));
    const DepthHistogram alone = computeDepthHistogram(tracer, depthHistogramRequest(tracer, stack, 0, {}, camera, kWidth, kHeight));
    ASSERT_NE(alone.layer(0), nullptr);
    EXPECT_LT(alone.layer(0)->nearest, 7.5f);
    EXPECT_FALSE(alone.suggestions.empty());

    // Another lens over the whole image hides layer 0 from primary rays: so does the histogram.
    stack.add(pluginLens("layer", LensRegion::rectangle({0.5f, 0.5f}, {1.f, 1.f}), {{"layers", "1-"}, {"rays", "primary"}}));
    const DepthHistogram underAnother =
        computeDepthHistogram(tracer, depthHistogramRequest(tracer, stack, 0, {}, camera, kWidth, kHeight));
    EXPECT_EQ(underAnother.layer(0), nullptr);
    ASSERT_NE(underAnother.layer(1), nullptr);
    EXPECT_EQ(underAnother.layer(1)->crossings, alone.layer(1)->crossings);

    // And the base policy's constraints hold for a bare region too.
    RayPolicy base;
    base.query(RayType::Primary).layerMask = layerBit(1);
    const DepthHistogram onlyInner = computeDepthHistogram(tracer, regionRequest(camera, region, base));
    ASSERT_EQ(onlyInner.layers.size(), 1u);
    EXPECT_EQ(onlyInner.layers[0].layer, 1);

    EXPECT_THROW(depthHistogramRequest(tracer, stack, 2, {}, camera, kWidth, kHeight), Error);
    EXPECT_THROW(depthHistogramRequest(tracer, stack, 0, {}, camera, 0, kHeight), Error);
}

TEST(DepthHistogram, EmptyRegionsAndMissesGiveAnEmptyHistogram) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    for (const LensRegion &region : {LensRegion::rectangle({3.f, 3.f}, {0.2f, 0.2f}),
                                     LensRegion::rectangle({0.5f, 0.5f}, {0.f, 0.f}),
                                     LensRegion::ellipse({0.5f, 0.5f}, {1e-6f, 1e-6f})}) {
        const DepthHistogram h = computeDepthHistogram(tracer, regionRequest(camera, region));
        EXPECT_TRUE(h.isEmpty());
        EXPECT_EQ(h.raysSampled, 0u);
        EXPECT_EQ(h.binCount(), 0);
        EXPECT_EQ(h.binWidth(), 0.f);
        EXPECT_TRUE(h.layers.empty());
        EXPECT_TRUE(h.suggestions.empty());
    }
    // Rays that all leave the scene: sampled, none hit.
    const Camera skyward = Camera::lookAt({0.f, 1.f, 8.f}, {0.f, 9.f, 0.f}, {0.f, 1.f, 0.f}, 30.f);
    const DepthHistogram sky =
        computeDepthHistogram(tracer, regionRequest(skyward, LensRegion::rectangle({0.5f, 0.2f}, {0.3f, 0.2f})));
    EXPECT_GT(sky.raysSampled, 0u);
    EXPECT_EQ(sky.raysHit, 0u);
    EXPECT_TRUE(sky.isEmpty());
    EXPECT_TRUE(sky.suggestions.empty());

    DepthHistogramRequest noImage = regionRequest(camera, LensRegion::ellipse({0.5f, 0.5f}, {0.2f, 0.2f}));
    noImage.width = 0;
    EXPECT_THROW(computeDepthHistogram(tracer, noImage), Error);
}

TEST(DepthHistogram, SettingsCapCrossingsFixTheRangeAndAStopTokenCancels) {
    const Scene scene = loadScene("builtin:onion");
    const Tracer tracer(scene);
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    DepthHistogramRequest request = regionRequest(camera, LensRegion::ellipse({0.5f, 0.47f}, {0.1f, 0.13f}));

    // Every ray crosses nine surfaces (four spheres twice, then the floor); keep two of them.
    request.settings.maxCrossings = 2;
    request.settings.pixelStep = 3;
    const DepthHistogram capped = computeDepthHistogram(tracer, request);
    EXPECT_EQ(capped.pixelStep, 3);
    EXPECT_EQ(capped.raysTruncated, capped.raysHit);
    EXPECT_EQ(capped.crossings, 2u * capped.raysHit);
    ASSERT_NE(capped.layer(1), nullptr);
    EXPECT_EQ(capped.layer(2), nullptr) << "the core lies behind the second crossing";

    // A fixed range bins only what lies inside it.
    request.settings.maxCrossings = 64;
    request.settings.tNear = 3.f;
    request.settings.tFar = 3.5f;
    request.settings.binCount = 50;
    const DepthHistogram ranged = computeDepthHistogram(tracer, request);
    EXPECT_EQ(ranged.tNear, 3.f);
    EXPECT_EQ(ranged.tFar, 3.5f);
    EXPECT_EQ(ranged.binCount(), 50);
    EXPECT_NEAR(ranged.binWidth(), 0.01f, 1e-6f);
    EXPECT_EQ(ranged.crossings, 2u * ranged.raysHit) << "skin and flesh fronts only";

    std::stop_source stop;
    stop.request_stop();
    const DepthHistogram cancelled = computeDepthHistogram(tracer, request, stop.get_token());
    EXPECT_TRUE(cancelled.cancelled);
    EXPECT_TRUE(cancelled.isEmpty());
}

TEST(DepthHistogram, ApplyLensDistanceSetsAndCommitsTheLayerLensDistance) {
    const std::shared_ptr<Lens> layer = pluginLens("layer", LensRegion::ellipse({0.5f, 0.5f}, {0.2f, 0.2f}));
    applyLensDistance(*layer, 3.25f);
    EXPECT_EQ(layer->property(kLensDistanceProperty).toReal(), 3.25);
    EXPECT_EQ(layer->snapshot()->contribution.visibility[size_t(RayType::Primary)].tMin, 3.25f);
    const uint64_t version = layer->snapshot()->version;
    EXPECT_THROW(applyLensDistance(*layer, -1.f), Error);
    EXPECT_EQ(layer->snapshot()->version, version) << "a rejected value keeps the committed snapshot";

    const std::shared_ptr<Lens> achromatic = pluginLens("achromatic", LensRegion::ellipse({0.5f, 0.5f}, {0.2f, 0.2f}));
    EXPECT_THROW(applyLensDistance(*achromatic, 1.f), Error);
}
