#pragma once
/// \file Animation.h
/// An animation of one view: a duration and a frame rate, keyframes of the camera (or an orbit
/// about an axis) and keyframes of lens properties, regions and enabled flags, each lens named
/// by its index in the session's lens stack. Frame i shows time i / frameRate, for
/// i = 0 … frameCount() − 1 with frameCount() = round(duration · frameRate), so a turntable of
/// N frames over one turn never repeats its first frame at the end.
///
/// Every keyed value (a camera field, one lens property, one region field) is a track of its
/// own: the keyframes that give it. Before a track's first keyframe its first value holds, after
/// the last its last; between two keyframes the value moves by the easing of the earlier one
/// (PropertyInterpolation.h). What no keyframe gives stays as the session has it. Cameras are in
/// world units, as session files have them; regions in normalised image coordinates.
///
/// Files: AnimationFile.h. Applying a frame to a view's camera and lenses: AnimationPlayer.h.

#include <mvcl/core/Export.h>

#include <mvcl/io/LensStackFile.h>
#include <mvcl/lens/LensRegion.h>
#include <mvcl/lens/PropertyInterpolation.h>
#include <mvcl/lens/PropertyValue.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mvcl {

/// Camera fields at one time; the fields left empty are not keyed by this keyframe.
struct CameraKeyframe {
    double time = 0.0; ///< seconds, in [0, duration]
    Easing easing = Easing::Linear; ///< toward the next keyframe of each field
    std::optional<glm::vec3> eye;   ///< world space
    std::optional<glm::vec3> target;
    std::optional<glm::vec3> up;
    std::optional<float> verticalFovDegrees;
};

/// The camera turned about an axis: eye and up rotate about the line through `center` (the
/// camera's target at that time when empty) along `axis` (the camera's up when empty), by an
/// angle going from `fromDegrees` at `startTime` to `toDegrees` at `endTime` (the duration when
/// empty). Applied after the camera keyframes.
struct CameraOrbit {
    std::optional<glm::vec3> axis;   ///< world space, any length > 0
    std::optional<glm::vec3> center; ///< world space
    double fromDegrees = 0.0;
    double toDegrees = 360.0;
    double startTime = 0.0;
    std::optional<double> endTime;
    Easing easing = Easing::Linear;
};

/// One lens's keyed values at one time.
struct MVCL_EXPORT LensKeyframe {
    double time = 0.0;
    Easing easing = Easing::Linear;
    /// (property name, value of the lens's declared type).
    std::vector<std::pair<std::string, PropertyValue>> properties;
    std::optional<bool> enabled;                 ///< steps
    std::optional<glm::vec2> center;             ///< region centre (moves a polygon)
    std::optional<glm::vec2> size;               ///< rectangle and ellipse only
    std::optional<float> feather;                ///< px
    std::optional<std::vector<glm::vec2>> points; ///< polygon only, as many as the lens has

    /// The value of `name` this keyframe gives, or nullptr.
    const PropertyValue *property(std::string_view name) const;
};

/// The keyframes of one lens of the stack, in time order.
struct LensTrack {
    int lens = 0; ///< index in the stack, bottom = 0
    std::vector<LensKeyframe> keyframes;
};

class MVCL_EXPORT Animation {
public:
    /// One second at 30 frames per second, nothing keyed.
    Animation() = default;

    /// Seconds, > 0.
    double duration() const { return m_duration; }
    void setDuration(double seconds) { m_duration = seconds; }
    /// Frames per second, > 0.
    double frameRate() const { return m_frameRate; }
    void setFrameRate(double framesPerSecond) { m_frameRate = framesPerSecond; }
    /// round(duration · frameRate), at least 1.
    int frameCount() const;
    /// frame / frameRate: the time frame `frame` shows.
    double frameTime(int frame) const;

    const std::vector<CameraKeyframe> &cameraKeyframes() const { return m_cameraKeyframes; }
    /// Inserted in time order; a keyframe at the time of an existing one replaces the fields it gives.
    void addCameraKeyframe(const CameraKeyframe &keyframe);
    const std::optional<CameraOrbit> &orbit() const { return m_orbit; }
    void setOrbit(std::optional<CameraOrbit> orbit) { m_orbit = std::move(orbit); }

    const std::vector<LensTrack> &lensTracks() const { return m_lensTracks; }
    /// Inserted in time order into the track of `keyframe`'s lens; at the time of an existing
    /// keyframe, the values given replace that keyframe's.
    void addLensKeyframe(int lens, const LensKeyframe &keyframe);
    /// A lens track whose first keyframe shows `from` and whose last shows `to` on the last frame.
    void addSweep(int lens, const std::string &property, const PropertyValue &from, const PropertyValue &to);

    /// N frames of one full turn about the camera's up axis through its target, at `frameRate`.
    static Animation turntable(int frameCount, double frameRate);

    /// The camera at `time`: `base` (world units) with the keyed fields and the orbit applied.
    LensStackCamera cameraAt(double time, const LensStackCamera &base) const;
    /// Whether the camera changes at all.
    bool movesCamera() const { return !m_cameraKeyframes.empty() || m_orbit.has_value(); }

    /// The keyed property values of `track`'s lens at `time`, with the declarations of `table`
    /// (the lens's); properties no keyframe gives are not in the list.
    static std::vector<std::pair<std::string, PropertyValue>> propertiesAt(const LensTrack &track, double time,
                                                                           const PropertyTable &table);
    /// `base` with the keyed region fields of `track` at `time`.
    static LensRegion regionAt(const LensTrack &track, double time, const LensRegion &base);
    /// The keyed enabled flag at `time`, if any keyframe gives one.
    static std::optional<bool> enabledAt(const LensTrack &track, double time);

private:
    double m_duration = 1.0;
    double m_frameRate = 30.0;
    std::vector<CameraKeyframe> m_cameraKeyframes;
    std::optional<CameraOrbit> m_orbit;
    std::vector<LensTrack> m_lensTracks;
};

} // namespace mvcl
