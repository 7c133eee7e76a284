#pragma once
// Case 28: nested layers a hair apart. Two UV spheres, the outer one (layer 0) of radius
// (1 + g)·k around the inner one (layer 1) of radius k, at (T, T, T) in world space and
// re-centred in double as the glTF loader does. Rendered from outside with one primary ray per
// pixel: no pixel may show the inner layer, and shadow and reflection rays spawned from the outer
// layer may not be stopped by either layer (both spheres are convex and the light is outside).
// Shared by the GoogleTest suite and mvcl-robustness-digest, like RobustnessCases.h.

#include <mvcl/model/Scene.h>

#include <cstdint>
#include <string>
#include <vector>

namespace mvcl::robustness {

enum class NestedTessellation {
    Equal,     ///< both 48 rings × 96 segments: the outer vertices are the inner ones scaled
    Different, ///< outer 48 × 96, inner 64 × 128: the outer's flat facets cut inside the inner's vertices
};

struct NestedLayerConfig {
    double gap = 0.0;         ///< g: the outer radius is (1 + g)·k
    double scale = 1.0;       ///< k
    double translation = 0.0; ///< T, world space, removed again by the re-centring
    NestedTessellation tessellation = NestedTessellation::Equal;
    /// Scene::layerContact relative to the scene's size (0 = off). Different tessellations need
    /// about the outer facets' sagitta.
    double contactTolerance = 0.0;
    int width = 100;
    int height = 100;
};

struct NestedLayerCounts {
    uint64_t modelPixels = 0;    ///< primary rays that hit anything
    uint64_t innerShowing = 0;   ///< primary rays whose hit is not on layer 0
    uint64_t shadowAcne = 0;     ///< lit outer points (n·l > 0.05) whose shadow ray is occluded
    uint64_t reflectionAcne = 0; ///< rays reflected off the outer layer that hit anything
    uint64_t refractionNotInner = 0; ///< refracted rays whose first hit is not layer 1 (reported)
    uint64_t nonFinite = 0;      ///< non-finite t or hit point
    uint64_t hash = 0;           ///< sum of hitHash() over every primary, shadow and secondary query
    bool pass() const {
        return innerShowing == 0 && shadowAcne == 0 && reflectionAcne == 0 && nonFinite == 0;
    }
};

std::vector<double> nestedLayerGaps();         ///< 0, 1e-7, 3e-7, 1e-6, 1e-5, 1e-4, 1e-3
std::vector<double> nestedLayerScales();       ///< 1e-7, 1e-3, 1, 1e3, 1e7
std::vector<double> nestedLayerTranslations(); ///< 0, 1e4, 1e7
/// The contact tolerance the map uses for different tessellations: 1.5 × the outer sphere's
/// largest facet sagitta (the diagonal's), relative to the scene's size.
double nestedLayerDifferentTolerance();
/// Whether the refracted ray must reach layer 1 first: g·k ≥ 32·ulp(k) (the guarantee of case 17).
bool nestedRefractionRequired(const NestedLayerConfig &config);

Scene makeNestedSpheres(const NestedLayerConfig &config);
NestedLayerCounts runNestedLayerCell(const NestedLayerConfig &config, int threads);
std::string describe(const NestedLayerConfig &config);

} // namespace mvcl::robustness
