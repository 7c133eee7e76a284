#pragma once
/// \file PixelProbe.h
/// A testing helper for lens authors: what does a given pixel's ray do under a stack, without
/// rendering an image.
///
///     const PixelProbe probe(stack, lensContextOf(scene, camera, 64, 64));
///     EXPECT_EQ(probe.policy(32, 32).ray.query(RayType::Primary).layerMask, layersFrom(1));
///     EXPECT_FLOAT_EQ(probe.lensWeight(0, 32, 32), 1.f);
///     EXPECT_EQ(probe.primaryHitLayer(tracer, camera, 32, 32), 1);
///
/// Built from a LensContext (ViewLensContext.h), every lens contributes as it does in a render
/// of that scene and view (Lens::snapshotIn, as RenderSession does), so a lens that depends on
/// the view or the scene behaves the same under the probe as in an image. Built from a size
/// alone, lenses keep the contribution they committed in their own context.

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/view/Picking.h>

#include <optional>
#include <span>
#include <vector>

namespace mvcl {

class Camera;
class Tracer;
struct LensContext;

/// A lens of the stack and its share of a pixel.
struct LensWeight {
    int lensIndex = 0; ///< index in the stack, bottom first
    float weight = 0.f; ///< sum of the pixel's term weights whose policy includes the lens (0..1)
};

class MVCL_EXPORT PixelProbe {
public:
    /// Lenses as committed (in the context each was committed in), at width × height.
    PixelProbe(const LensStack &stack, int width, int height, const RayPolicy &base = {});
    /// Lenses as they are in `context` (its image size, camera and scene), as a render shows them.
    PixelProbe(const LensStack &stack, const LensContext &context, const RayPolicy &base = {});

    const PolicyMap &map() const { return m_map; }
    /// Policies and weights blended at the pixel.
    std::span<const PolicyTerm> terms(int x, int y) const { return m_map.terms(x, y); }
    /// The pixel's dominant policy (the only one away from feathered edges).
    const PixelPolicy &policy(int x, int y) const { return m_map.dominantPolicy(x, y); }
    /// Lenses (bit i = stack index i) in the pixel's dominant policy.
    uint64_t lensSet(int x, int y) const { return policy(x, y).lensSet; }
    /// How much of the pixel lens `lensIndex` covers: 1 inside it, 0 outside, between on a
    /// feathered edge (the weights of the pixel's blended policies that include it).
    float lensWeight(int lensIndex, int x, int y) const;
    /// Every lens with a weight above 0 at the pixel, bottom first.
    std::vector<LensWeight> lenses(int x, int y) const;

    /// Traces the primary ray through the pixel centre (after ray shaping) under its dominant
    /// policy. No shading, no secondary rays.
    std::optional<Hit> primaryHit(const Tracer &tracer, const Camera &camera, int x, int y) const;
    /// Layer of the mesh the primary ray hits, -1 for spheres/planes, nullopt for a miss.
    std::optional<int> primaryHitLayer(const Tracer &tracer, const Camera &camera, int x,
                                       int y) const;
    /// Everything about the primary hit (names, distance, world position, normals); see
    /// Picking.h. Same ray and query as primaryHit().
    PickResult pick(const Tracer &tracer, const Camera &camera, int x, int y) const;
    /// Radiance of one sample through the pixel centre, blended over the pixel's terms.
    glm::vec3 radiance(const Tracer &tracer, const Camera &camera, int x, int y) const;

private:
    PolicyMap m_map;
};

} // namespace mvcl
