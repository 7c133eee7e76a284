#pragma once
/// \file PolicyComposition.h
/// The composition rules of the lens stack as pure functions, so every rule has its own tests:
///   ray shaping  — maps chain so that the upper lens looks at the image of the lower one;
///   visibility   — intersection of constraints (commutative, associative, idempotent);
///   shading      — the upper lens overrides the fields it sets;
///   colour       — function composition bottom → top (upper ∘ lower).

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensContribution.h>
#include <mvcl/lens/PixelPolicy.h>

namespace mvcl {

/// Hits must satisfy both: layer masks AND-ed, t-ranges intersected, clip volumes of both
/// (identical volumes kept once). When the volumes together exceed kMaxClipVolumes, volumes
/// whose intersection keeps their shape are merged (two kept-inside boxes; two half-spaces with
/// the same normal and keep); any of `b`'s that still do not fit are left out and counted in
/// `*droppedClips`. Never throws: composition runs on the render path, and LensStack::compose
/// reports the count as PolicyMap::droppedClipVolumes().
MVCL_EXPORT RayQuery intersectQueries(const RayQuery &a, const RayQuery &b, int *droppedClips = nullptr);

/// Colour map that applies `lower` first, then `upper`.
MVCL_EXPORT ColorPolicy composeColor(const ColorPolicy &lower, const ColorPolicy &upper);

/// `below` with `lens` applied on top of it.
/// Clip volumes that do not fit are counted in `*droppedClips` (see intersectQueries).
MVCL_EXPORT PixelPolicy applyContribution(const PixelPolicy &below, const LensContribution &lens,
                              int *droppedClips = nullptr);

} // namespace mvcl
