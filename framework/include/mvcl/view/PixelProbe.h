#pragma once
/// \file PixelProbe.h
/// A testing helper for lens authors: what does a given pixel's ray do under a stack, without
/// rendering an image.
///
///     PixelProbe probe(stack, 64, 64);
///     EXPECT_EQ(probe.policy(32, 32).ray.query(RayType::Primary).layerMask, layersFrom(1));
///     EXPECT_EQ(probe.primaryHitLayer(tracer, camera, 32, 32), 1);

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/view/Picking.h>

#include <optional>
#include <span>

namespace mvcl {

class Camera;
class Tracer;

class MVCL_EXPORT PixelProbe {
public:
    PixelProbe(const LensStack &stack, int width, int height, const RayPolicy &base = {});

    const PolicyMap &map() const { return m_map; }
    /// Policies and weights blended at the pixel.
    std::span<const PolicyTerm> terms(int x, int y) const { return m_map.terms(x, y); }
    /// The pixel's dominant policy (the only one away from feathered edges).
    const PixelPolicy &policy(int x, int y) const { return m_map.dominantPolicy(x, y); }
    /// Lenses (bit i = stack index i) in the pixel's dominant policy.
    uint64_t lensSet(int x, int y) const { return policy(x, y).lensSet; }

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
