#pragma once
/// \file ViewKeyframes.h
/// Keyframes taken from a view as it is: its camera, and a lens's committed properties, region
/// and enabled flag. An interactive "add keyframe" adds them to an Animation, which
/// writeAnimationFile saves and AnimationPlayer plays back.

#include <mvcl/core/Export.h>

#include <mvcl/controller/ViewCoordinates.h>
#include <mvcl/io/Animation.h>
#include <mvcl/view/Camera.h>

namespace mvcl {

class Lens;

/// Every field of `camera` (scene space) at `seconds`, in world units.
MVCL_EXPORT CameraKeyframe cameraKeyframeOf(const Camera &camera, const ViewCoordinates &coordinates, double seconds);
/// Every committed property of `lens`, its region's centre and size (a polygon's points), its
/// feather and its enabled flag, at `seconds`.
MVCL_EXPORT LensKeyframe lensKeyframeOf(const Lens &lens, double seconds);

} // namespace mvcl
