#pragma once
/// \file LayerContactProbe.h
/// Finds layers whose surfaces touch or nearly touch (an organ wall shared by two layers, a part
/// seated in its housing) and suggests a Scene::layerContact for them. `mvcl-render --info` prints
/// it. Triangulations that differ on the two sides of a contact poke through each other by up to
/// their facets' sagitta; equal triangulations need no tolerance (the tracer's layer priority
/// within the error bound covers them).

#include <mvcl/core/Export.h>

#include <mvcl/model/LayerContact.h>

#include <cstddef>
#include <vector>

namespace mvcl {

class Tracer;

struct NearCoincidentLayers {
    int outerLayer = 0; ///< the lower layer number
    int innerLayer = 0;
    std::size_t samples = 0;      ///< triangle centroids of one layer with the other within reach
    std::size_t sampled = 0;      ///< triangle centroids probed in the two layers
    double maxSeparation = 0.0;   ///< scene units: the largest distance among those samples
};

struct LayerContactReport {
    std::vector<NearCoincidentLayers> pairs; ///< by (outerLayer, innerLayer)
    /// 1.5 × the largest separation of the pairs found, relative to the scene's size; off when
    /// no pair was found or that is below kNoToleranceBelow (surfaces that coincide up to float
    /// rounding, which layer priority within the error bound already resolves).
    LayerContact suggested;
    static constexpr double kNoToleranceBelow = 1e-6;
};

struct LayerContactProbeSettings {
    /// Triangles probed per mesh (evenly spaced through its index list).
    std::size_t samplesPerMesh = 2000;
    /// How far to look along ± the face normal, relative to the scene's size.
    double reach = 1e-3;
    /// A pair is near-coincident when at least this fraction of one of its meshes' samples finds
    /// the other layer within reach.
    double minimumFraction = 0.05;
};

/// Probes through the centroids of each mesh's triangles along the face normal for the nearest
/// surface of another layer within reach on either side (a coincident one included).
/// Deterministic; a few queries per sample.
MVCL_EXPORT LayerContactReport probeLayerContacts(const Tracer &tracer, const LayerContactProbeSettings &settings = {});

} // namespace mvcl
