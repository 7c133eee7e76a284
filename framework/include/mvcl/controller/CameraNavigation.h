#pragma once
/// \file CameraNavigation.h
/// The camera moves of an interactive view as pure functions of a camera (scene space): orbit
/// about the target, pan, zoom about a point, frame everything, preset views. The Controller
/// maps pointer and key input onto them; they keep the camera's up vector and field of view.

#include <mvcl/core/Export.h>

#include <mvcl/core/Bounds3.h>
#include <mvcl/view/Camera.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace mvcl {

/// Views along the scene's axes (glTF convention: +y up, the front faces +z).
enum class ViewPreset : uint8_t {
    Front,  ///< from +z looking toward −z
    Back,   ///< from −z
    Left,   ///< from −x
    Right,  ///< from +x
    Top,    ///< from +y, −z up on screen
    Bottom, ///< from −y, +z up on screen
};

MVCL_EXPORT const char *viewPresetName(ViewPreset preset);

/// Turntable orbit: the eye turns about the target by `yawRadians` about the camera's up
/// vector and by `pitchRadians` toward the up vector (positive: the eye rises). The distance to
/// the target does not change; the pitch stops short of the poles so the view never flips.
MVCL_EXPORT Camera orbitCamera(const Camera &camera, float yawRadians, float pitchRadians);

/// Moves eye and target together so that points at the target's depth follow a pointer moved
/// by `pixelOffset` (x right, y down) in a view `viewSize` pixels large.
MVCL_EXPORT Camera panCamera(const Camera &camera, const glm::vec2 &pixelOffset, const glm::ivec2 &viewSize);

/// Scales the camera about `anchor` (scene space): eye and target move toward it by `factor`
/// (< 1 zooms in, > 1 out). The anchor keeps its place in the image, so a point under the
/// pointer stays under it.
MVCL_EXPORT Camera zoomCamera(const Camera &camera, float factor, const glm::vec3 &anchor);

/// The same view direction, up and field of view, at the distance that fits all of `bounds`.
MVCL_EXPORT Camera framedCamera(const Camera &camera, const Bounds3f &bounds, float aspect);

/// A preset direction framing all of `bounds`, with the camera's field of view.
MVCL_EXPORT Camera presetCamera(const Camera &camera, ViewPreset preset, const Bounds3f &bounds, float aspect);

} // namespace mvcl
