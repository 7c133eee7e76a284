#pragma once
/// \file PolicyComposition.h
/// The composition rules of BRIEF §3 as pure functions, so every rule has its own tests:
///   ray shaping  — maps chain so that the upper lens looks at the image of the lower one;
///   visibility   — intersection of constraints (commutative, associative, idempotent);
///   shading      — the upper lens overrides the fields it sets;
///   colour       — function composition bottom → top (upper ∘ lower).

#include <mvcl/lens/LensContribution.h>
#include <mvcl/lens/PixelPolicy.h>

namespace mvcl {

/// Hits must satisfy both: layer masks AND-ed, t-ranges intersected, clip volumes of both
/// (identical volumes kept once). Throws mvcl::Error("lens stack", ...) when the clip volumes
/// together exceed kMaxClipVolumes.
RayQuery intersectQueries(const RayQuery &a, const RayQuery &b);

/// Colour map that applies `lower` first, then `upper`.
ColorPolicy composeColor(const ColorPolicy &lower, const ColorPolicy &upper);

/// `below` with `lens` applied on top of it.
PixelPolicy applyContribution(const PixelPolicy &below, const LensContribution &lens);

} // namespace mvcl
