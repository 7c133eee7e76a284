#include <mvcl/view/DepthHistogram.h>

#include "DepthHistogramAnalysis_p.h"

#include <mvcl/core/Error.h>
#include <mvcl/core/FloatBits.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/lens/Lens.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Picking.h>
#include <mvcl/view/ViewLensContext.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace mvcl {

namespace {

constexpr const char *kSource = "depth histogram";

struct SampleGrid {
    std::vector<glm::ivec2> pixels;
    /// Pairs of sampled pixels next to each other on the grid (indices into `pixels`).
    std::vector<std::pair<uint32_t, uint32_t>> neighbours;
    int step = 1;
};

/// Pixels on a step × step grid over the region's bounding box whose centre the region covers.
/// The grid starts half a step in, so it sits evenly inside the box.
SampleGrid samplePixels(const LensRegion &region, int width, int height, const DepthHistogramSettings &settings) {
    SampleGrid grid;
    const PixelRect box = region.pixelBounds(width, height);
    if (box.isEmpty()) return grid;
    const double boxPixels = double(box.x1 - box.x0) * double(box.y1 - box.y0);
    grid.step = settings.pixelStep > 0
                    ? settings.pixelStep
                    : std::max(1, int(std::ceil(std::sqrt(boxPixels / double(std::max(settings.targetRays, 1))))));
    const int x0 = box.x0 + grid.step / 2, y0 = box.y0 + grid.step / 2;
    const int columns = x0 < box.x1 ? (box.x1 - x0 + grid.step - 1) / grid.step : 0;
    std::vector<int64_t> previousRow(std::size_t(columns), -1), row(std::size_t(columns), -1);
    for (int y = y0; y < box.y1; y += grid.step) {
        for (int c = 0; c < columns; ++c) {
            const int x = x0 + c * grid.step;
            row[std::size_t(c)] = -1;
            if (!(region.coverage({float(x) + 0.5f, float(y) + 0.5f}, width, height) > 0.f)) continue;
            const auto index = uint32_t(grid.pixels.size());
            row[std::size_t(c)] = index;
            grid.pixels.push_back({x, y});
            if (c > 0 && row[std::size_t(c - 1)] >= 0) grid.neighbours.emplace_back(uint32_t(row[std::size_t(c - 1)]), index);
            if (previousRow[std::size_t(c)] >= 0) grid.neighbours.emplace_back(uint32_t(previousRow[std::size_t(c)]), index);
        }
        std::swap(row, previousRow);
    }
    return grid;
}

/// Rays are walked in batches of this many, each batch on one thread into its own storage.
constexpr std::size_t kRaysPerBatch = 32;

/// Every surface the ray crosses within the query, nearest first: closest hit after closest
/// hit, each starting just past the previous one (as the integrator's transparent-shadow
/// walk does), up to maxCrossings; appended to `out` as its next ray.
void walkCrossings(const Tracer &tracer, const Ray &ray, RayQuery query, int maxCrossings, detail::RayCrossings &out) {
    int n = 0;
    while (n < maxCrossings) {
        Hit hit;
        if (!tracer.closestHit(ray, query, hit)) break;
        const bool frontFacing = glm::dot(tracer.interaction(ray, hit).geometricNormal, ray.direction) < 0.f;
        out.t.push_back(hit.t);
        out.layer.push_back(hit.layer);
        out.surface.push_back(detail::surfaceKey(hit, frontFacing));
        ++n;
        query.tMin = nextFloatUp(hit.t);
        if (query.tMin > query.tMax) break;
    }
    out.begin.push_back(uint32_t(out.t.size()));
    out.truncated.push_back(n == maxCrossings && query.tMin <= query.tMax && tracer.anyHit(ray, query));
}

/// The batches' rays in order, as one set.
detail::RayCrossings concatenate(const std::vector<detail::RayCrossings> &batches, const SampleGrid &grid) {
    detail::RayCrossings rays;
    for (const detail::RayCrossings &batch : batches) {
        const auto offset = uint32_t(rays.t.size());
        for (uint32_t r = 0; r < batch.rayCount(); ++r) rays.begin.push_back(offset + batch.begin[r + 1]);
        rays.t.insert(rays.t.end(), batch.t.begin(), batch.t.end());
        rays.layer.insert(rays.layer.end(), batch.layer.begin(), batch.layer.end());
        rays.surface.insert(rays.surface.end(), batch.surface.begin(), batch.surface.end());
        rays.truncated.insert(rays.truncated.end(), batch.truncated.begin(), batch.truncated.end());
    }
    rays.neighbours = grid.neighbours;
    return rays;
}

} // namespace

float DepthHistogram::binStart(int i) const {
    if (counts.empty()) return tNear;
    return float(double(tNear) + (double(tFar) - double(tNear)) * double(i) / double(counts.size()));
}

const LayerDepths *DepthHistogram::layer(int id) const {
    for (const LayerDepths &l : layers)
        if (l.layer == id) return &l;
    return nullptr;
}

DepthHistogramRequest depthHistogramRequest(const Tracer &tracer, const LensStack &stack, int lensIndex,
                                            const RayPolicy &base, const Camera &camera, int width, int height,
                                            const DepthHistogramSettings &settings) {
    const std::shared_ptr<Lens> &lens = stack.lens(lensIndex);
    if (width <= 0 || height <= 0) throw Error(kSource, "the image size must be positive");
    DepthHistogramRequest request;
    request.camera = camera;
    request.width = width;
    request.height = height;
    request.region = lens->snapshot()->region;
    request.base = base;
    request.settings = settings;
    // The lens's own constraints are what the histogram helps to choose, so it is left out;
    // every other lens over a pixel still shapes and constrains that pixel's ray.
    LensStack others = stack;
    others.remove(lensIndex);
    if (!others.isEmpty())
        request.surroundings = std::make_shared<const PolicyMap>(
            others.compose(lensContextOf(tracer.scene(), camera, width, height), base));
    return request;
}

DepthHistogram computeDepthHistogram(const Tracer &tracer, const DepthHistogramRequest &request, std::stop_token stop) {
    const auto started = std::chrono::steady_clock::now();
    const int width = request.width, height = request.height;
    if (width <= 0 || height <= 0) throw Error(kSource, "the image size must be positive");
    const PolicyMap *surroundings = request.surroundings.get();
    if (surroundings && (surroundings->width() != width || surroundings->height() != height))
        throw Error(kSource, "the surrounding policies are " + std::to_string(surroundings->width()) + "×" +
                                 std::to_string(surroundings->height()) + ", the image " + std::to_string(width) +
                                 "×" + std::to_string(height));

    const DepthHistogramSettings &settings = request.settings;
    const SampleGrid grid = samplePixels(request.region, width, height, settings);
    const int maxCrossings = std::max(settings.maxCrossings, 1);
    PixelPolicy basePolicy;
    basePolicy.ray = request.base;
    std::vector<detail::RayCrossings> batches((grid.pixels.size() + kRaysPerBatch - 1) / kRaysPerBatch);
    parallelFor(batches.size(), settings.threads, [&](std::size_t batch) {
        if (stop.stop_requested()) return;
        const std::size_t end = std::min(grid.pixels.size(), (batch + 1) * kRaysPerBatch);
        for (std::size_t r = batch * kRaysPerBatch; r < end; ++r) {
            const glm::ivec2 p = grid.pixels[r];
            const PixelPolicy &policy = surroundings ? surroundings->dominantPolicy(p.x, p.y) : basePolicy;
            walkCrossings(tracer, pixelCentreRay(request.camera, policy, p.x, p.y, width, height),
                          policy.ray.query(RayType::Primary), maxCrossings, batches[batch]);
        }
    });

    DepthHistogram histogram;
    if (stop.stop_requested()) {
        histogram.cancelled = true;
    } else {
        histogram = detail::analyseCrossings(concatenate(batches, grid), tracer.scene().layers, settings);
    }
    histogram.pixelStep = grid.step;
    histogram.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
    return histogram;
}

void applyLensDistance(Lens &lens, float distance) {
    // setProperty names the lens and the problem (no such property, wrong type, out of range).
    lens.setProperty(kLensDistanceProperty, PropertyValue::real(double(distance)));
    lens.commit();
}

} // namespace mvcl
