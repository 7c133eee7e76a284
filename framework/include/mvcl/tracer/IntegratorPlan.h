#pragma once
/// \file IntegratorPlan.h
/// Which stages of the Whitted integrator one RayPolicy needs in one scene. A caller computes it
/// once per policy and render pass (WhittedIntegrator::plan) and hands it to every radiance()
/// call of that policy, so no stage decision is taken per ray.
///
/// Leaving a stage out never changes a pixel: a stage is left out only where running it is
/// certain to give the same value (a shadow ray that nothing can hit passes the full light; an
/// any-hit query answers exactly what a walk over opaque occluders answers; a hit whose material
/// neither reflects nor refracts spawns no secondary ray; the identity colour map maps a colour
/// to itself).

#include <mvcl/tracer/RayPolicy.h>

#include <cstdint>

namespace mvcl {

/// Whether the integrator leaves out the stages a policy does not need, or runs every stage
/// the way it would for a scene that needed all of them (only to measure what leaving them out
/// saves; the image is the same).
enum class StageSelection : uint8_t {
    SkipUnneeded,
    ForceAll,
};

/// How the light a hit receives from each light is shadowed.
enum class ShadowStage : uint8_t {
    /// No shadow rays: the policy turns shadows off, or the scene has no lights.
    Off,
    /// Nothing the policy's shadow query may hit exists, so every light passes fully; the light
    /// is added without casting the ray.
    Unoccluded,
    /// One any-hit query per light: every occluder the query may hit is opaque.
    AnyHit,
    /// Closest-hit queries along the shadow ray, each occluder passing its transparency.
    TransparentWalk,
};

struct IntegratorPlan {
    ShadowStage shadows = ShadowStage::AnyHit;
    /// What forcing every stage would do for shadows; the integrator counts the difference as
    /// skipped work (RayCounters::skippedShadowRays, skippedTransparentWalks).
    ShadowStage forcedShadows = ShadowStage::AnyHit;
    /// Ray types (rayTypeBit) whose hits may reflect or refract; at a hit of any other type the
    /// reflection/refraction stage is left out.
    uint8_t secondaryRayTypes = kAllRayTypes;
    /// The policy's colour map is applied (under SkipUnneeded only when it is not the identity).
    bool appliesColorMap = true;
    /// Layers whose primary hits are partly transparent (ShadingPolicy::layerOpacity < 1) and
    /// that primary rays may hit: the opacity stage runs only at hits on these.
    uint32_t translucentLayers = 0;
};

} // namespace mvcl
