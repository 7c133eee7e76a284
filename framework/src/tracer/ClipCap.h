#pragma once
// Private to the tracer: where a primary ray that ends on the inside of a closed mesh crossed
// the clip surface that opened the mesh, so that the integrator can draw a cap there.

#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>

#include <glm/vec3.hpp>

#include <optional>

namespace mvcl::detail {

struct ClipCap {
    float t = 0.f;          ///< along the ray, in units of its direction's length
    glm::vec3 normal{0.f};  ///< unit normal of the clip surface, facing the ray's origin
    ClipVolume::CapStyle style = ClipVolume::CapStyle::None;
    uint32_t layers = kAllLayers; ///< the capping volume's layers: only their solids get the cap
};

/// The points along `ray` that `query`'s clip volumes accept form runs; `hitT` (the closest
/// accepted hit) lies in one of them. Returns where that run begins, if it begins on the
/// surface of a capped clip volume after query.tMin: the ray crossed the cut there and, since
/// the hit is the inside of a closed mesh, it crossed into the solid. Otherwise nothing (the
/// run starts at the ray's origin or on an uncapped volume). Only volumes that act on `layer`
/// (the hit's) count: a spared layer is neither cut nor capped.
std::optional<ClipCap> clipCapBefore(const Ray &ray, const RayQuery &query, float hitT, uint32_t layer);

/// The cap a hit on `hitLayer` at `hitT` may lie behind: clipCapBefore for the hit's layer and
/// for the layers of the capped volumes that spare it (a spared solid inside a cut one is hidden
/// by the cut one's cap), the nearest of them. Whose solid it caps is for the caller to check
/// (ClipCap::layers).
std::optional<ClipCap> nearestClipCap(const Ray &ray, const RayQuery &query, float hitT, uint32_t hitLayer);

/// The first run of accepted points after query.tMin that begins on the surface of a capped
/// clip volume: where a ray that meets no accepted surface at all may still enter a solid's
/// section (a slab between two planes through a solid). Whether a solid is there is for the
/// caller to find out.
std::optional<ClipCap> firstCappedRunStart(const Ray &ray, const RayQuery &query);

/// True if any of `query`'s clip volumes draws caps.
bool hasCappedClip(const RayQuery &query);

} // namespace mvcl::detail
