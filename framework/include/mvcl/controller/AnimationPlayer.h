#pragma once
/// \file AnimationPlayer.h
/// Shows an Animation in a view: sets the view's lenses to their keyed values at a frame's time
/// (committing only the lenses whose state changes) and gives the frame's camera in scene
/// space. mvcl-render renders each frame after showFrame(); the viewer previews with showTime().
///
/// A frame that keys no camera gets the base camera itself (not a round trip through world
/// units), so a sweep renders exactly what a single render of the same lens values renders,
/// and a RenderSession re-traces only the pixels whose lenses changed.

#include <mvcl/core/Export.h>

#include <mvcl/controller/LensState.h>
#include <mvcl/controller/ViewCoordinates.h>
#include <mvcl/io/Animation.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/view/Camera.h>

#include <vector>

namespace mvcl {

class MVCL_EXPORT AnimationPlayer {
public:
    /// `lenses` shares the lens objects the animation edits; their committed state now is what
    /// no keyframe changes. `baseCamera` (scene space) is the camera no keyframe changes;
    /// `coordinates` convert the animation's world units to scene space.
    AnimationPlayer(Animation animation, const LensStack &lenses, const Camera &baseCamera,
                    const ViewCoordinates &coordinates);

    const Animation &animation() const { return m_animation; }
    const Camera &baseCamera() const { return m_baseCamera; }

    /// showTime(animation().frameTime(frame)).
    Camera showFrame(int frame);
    /// Sets and commits the keyed lens values at `seconds`; returns the camera (scene space).
    /// Throws mvcl::Error naming the lens when a value does not commit.
    Camera showTime(double seconds);
    /// The camera at `seconds` without touching the lenses.
    Camera cameraAt(double seconds) const;
    /// Every animated lens back to its state when the player was made.
    void restoreLenses();

private:
    Animation m_animation;
    LensStack m_lenses;
    Camera m_baseCamera;
    ViewCoordinates m_coordinates;
    std::vector<LensState> m_baseStates; ///< per lens of the stack
};

} // namespace mvcl
