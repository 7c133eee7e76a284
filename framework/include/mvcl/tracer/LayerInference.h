#pragma once
/// \file LayerInference.h
/// Automatic layers by containment and visibility ("onion peeling"): meshes that are not enclosed
/// by the others form layer k; remove them and repeat for k + 1. A sample point on a mesh is
/// enclosed when at least `hiddenFraction` of the rays cast from it in `directions` directions hit
/// some other remaining mesh (so a bone that shows through a joint from a few directions is still
/// "mostly hidden", hence deeper); a mesh is enclosed when at least `enclosedFraction` of its
/// samples are. Each inferred mesh gets a confidence (TriangleMesh::layerConfidence).

#include <mvcl/core/Export.h>

#include <cstddef>

namespace mvcl {

struct Scene;
class Tracer;

struct LayerInferenceSettings {
    int samplesPerMesh = 64;        ///< triangle centroids sampled per mesh
    float enclosedFraction = 0.6f;  ///< share of enclosed samples that makes a mesh "inside"
    /// Rays cast from each sample: the six axis directions, then more spread evenly over the
    /// sphere (Fibonacci points) up to this count.
    int directions = 26;
    /// A sample is enclosed when at least this share of its rays hit another remaining mesh
    /// (1 = all of them: a sample seen from outside along any direction is not enclosed).
    float hiddenFraction = 0.9f;
    int firstLayer = 0;             ///< layer given to the outermost peel
};

struct LayerInferenceResult {
    std::size_t meshesAssigned = 0;
    int layerCount = 0; ///< distinct layers produced
};

/// Assigns a layer to every mesh with LayerSource::Unassigned (the others are kept as they are
/// and act as occluders), and adds the layers to the scene's table.
/// Builds its own tracer over the scene when there is more than one part to peel.
MVCL_EXPORT LayerInferenceResult inferLayersByContainment(Scene &scene, const LayerInferenceSettings &settings = {});
/// The same with a tracer the caller already has, built over a scene with the same geometry as
/// `scene` (any layers): `scene` itself, or a copy of it that others keep querying while this
/// one changes. With Tracer(scene, tracer) afterwards, a load builds one BVH instead of two.
MVCL_EXPORT LayerInferenceResult inferLayersByContainment(Scene &scene, const Tracer &tracer,
                                                          const LayerInferenceSettings &settings = {});

} // namespace mvcl
