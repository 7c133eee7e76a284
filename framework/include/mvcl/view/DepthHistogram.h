#pragma once
/// \file DepthHistogram.h
/// The depth histogram of a layer lens: where the surfaces lie along the primary rays under the
/// lens, per layer, and values of the lens's `distance` (d) that fall in the gaps between them.
///
/// For pixels on a grid inside the lens's region, the primary ray is traced with every layer
/// visible: the lens's own visibility constraint (its layers and d) is left out, while the base
/// policy's constraints (and, for a lens in a stack, those of the other lenses over the pixel,
/// with their ray shaping) are kept. Each ray records its first hit and every surface crossing
/// behind it (closest hit after closest hit, each starting just past the previous one, up to
/// DepthHistogramSettings::maxCrossings). The crossings are binned over [tNear, tFar], in total
/// and per layer, and the suggestions for d are the empty (or near-empty) runs of bins between
/// populated ones and the places just before each layer's first hits.
///
/// For a viewer: build a DepthHistogramRequest on the UI thread (it copies what it needs: the
/// lens region and the other lenses' committed policies), then run computeDepthHistogram() on
/// any thread; the result is plain data. A std::stop_token cancels a computation made stale by
/// an edit.
///
///     DepthHistogramRequest request = depthHistogramRequest(tracer, stack, lensIndex, base, camera, w, h);
///     auto future = std::async(std::launch::async, [&tracer, request] {
///         return computeDepthHistogram(tracer, request);
///     });
///     ...
///     const DepthHistogram histogram = future.get();
///     if (!histogram.suggestions.empty())
///         applyLensDistance(*stack.lens(lensIndex), histogram.suggestions[0].distance);

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensRegion.h>
#include <mvcl/lens/PolicyMap.h>
#include <mvcl/tracer/RayPolicy.h>
#include <mvcl/view/Camera.h>

#include <cstdint>
#include <memory>
#include <stop_token>
#include <string>
#include <vector>

namespace mvcl {

class Lens;
class LensStack;
class Tracer;

/// One layer's share of the crossings.
struct LayerDepths {
    int layer = 0;
    std::string name;             ///< from the scene's LayerTable
    std::vector<uint32_t> counts; ///< crossings per bin (same bins as DepthHistogram::counts)
    uint64_t crossings = 0;
    uint32_t firstHits = 0; ///< sampled rays whose first hit is on this layer
    float nearest = 0.f;    ///< smallest t of its crossings
    float farthest = 0.f;   ///< largest t of its crossings
};

/// A value for the layer lens's `distance`.
struct DepthSuggestion {
    enum class Reason : uint8_t {
        EmptyRun,        ///< inside a run of empty or near-empty bins between populated ones
        LayerTransition, ///< just before a layer's first hits (layerAfter is that layer)
    };
    float distance = 0.f;
    Reason reason = Reason::EmptyRun;
    /// No sampled crossing lies strictly between gapBegin and gapEnd, and distance is inside.
    float gapBegin = 0.f;
    float gapEnd = 0.f;
    /// Sampled rays with crossings on both sides of distance: the rays whose visible surface
    /// the suggestion moves to one behind it. Suggestions are ranked by it.
    uint32_t raysSeparated = 0;
    /// The layer most separated rays cross last before distance, and the one most of them hit
    /// first beyond it (what a lens showing all layers would show there); -1 if none.
    int layerBefore = -1;
    int layerAfter = -1;
};

/// Plain data: copy it, keep it, show it.
struct MVCL_EXPORT DepthHistogram {
    float tNear = 0.f; ///< range of the bins (fitted to the crossings unless the settings fix it)
    float tFar = 0.f;
    std::vector<uint32_t> counts;   ///< crossings per bin; empty when nothing was hit
    std::vector<LayerDepths> layers; ///< layers with crossings, by id
    /// Best first: most rays separated, then nearest. At most DepthHistogramSettings::maxSuggestions.
    std::vector<DepthSuggestion> suggestions;

    uint32_t raysSampled = 0;   ///< pixels sampled under the region
    uint32_t raysHit = 0;       ///< of those, rays with at least one crossing
    uint32_t raysTruncated = 0; ///< rays stopped at maxCrossings (more surfaces behind)
    uint64_t crossings = 0;     ///< crossings in the bins
    int pixelStep = 0;          ///< the grid's spacing in pixels
    double milliseconds = 0.0;  ///< wall time of computeDepthHistogram()
    bool cancelled = false;     ///< stopped by the stop token; the rest is empty

    bool isEmpty() const { return counts.empty(); }
    int binCount() const { return int(counts.size()); }
    float binWidth() const { return counts.empty() ? 0.f : (tFar - tNear) / float(counts.size()); }
    /// Start of bin i (i = binCount() gives tFar).
    float binStart(int i) const;
    /// The layer's entry, or null if it has no crossings.
    const LayerDepths *layer(int id) const;
};

struct DepthHistogramSettings {
    /// Sample every pixelStep-th pixel in x and y; 0 picks the step that gives about
    /// targetRays rays over the region's bounding box.
    int pixelStep = 0;
    int targetRays = 4096;
    int binCount = 256;
    /// Crossings followed per ray (first hit included).
    int maxCrossings = 64;
    /// A bin counts as near-empty when it holds at most this fraction of the rays that hit.
    float nearEmptyFraction = 0.005f;
    int maxSuggestions = 8;
    /// Fixed bin range; when tFar ≤ tNear (the default) the range is fitted to the crossings.
    float tNear = 0.f;
    float tFar = 0.f;
    /// Threads of the worker pool (0 = all cores).
    int threads = 0;
};

/// Everything computeDepthHistogram() reads besides the tracer, by value.
struct DepthHistogramRequest {
    Camera camera;
    int width = 0; ///< image size the region and the pixels refer to
    int height = 0;
    /// Pixels whose centre it covers (coverage > 0) are sampled.
    LensRegion region;
    /// Its primary visibility constrains every ray (unless `surroundings` is set).
    RayPolicy base;
    /// Optional: per-pixel policies to trace with instead of `base` (the other lenses of a stack
    /// composed over the base, width × height); the pixel's dominant policy is used.
    std::shared_ptr<const PolicyMap> surroundings;
    DepthHistogramSettings settings;
};

/// The request for lens `lensIndex` of `stack`: its committed region, and the other lenses
/// composed over `base` as surroundings, each as it is in this view of the tracer's scene
/// (lensContextOf(), as a render shows it). Reads committed snapshots only, so it may run while
/// lenses are edited; throws mvcl::Error for a bad index or size.
MVCL_EXPORT DepthHistogramRequest depthHistogramRequest(const Tracer &tracer, const LensStack &stack, int lensIndex,
                                                        const RayPolicy &base, const Camera &camera, int width,
                                                        int height, const DepthHistogramSettings &settings = {});

/// Samples the rays and builds the histogram. Const on its inputs: any thread, any number at
/// once. An empty region (or one outside the image) gives an empty histogram. Throws
/// mvcl::Error for a non-positive image size or surroundings of another size.
MVCL_EXPORT DepthHistogram computeDepthHistogram(const Tracer &tracer, const DepthHistogramRequest &request,
                                     std::stop_token stop = {});

/// Name of the layer lens's distance property (plugins/layer).
inline constexpr const char *kLensDistanceProperty = "distance";

/// Sets the lens's `distance` to `distance` and commits (with whatever else is staged). Throws
/// mvcl::Error, keeping the previous snapshot, if the lens has no such property or the value is
/// out of its range.
MVCL_EXPORT void applyLensDistance(Lens &lens, float distance);

} // namespace mvcl
