#include <mvcl/controller/AnimationPlayer.h>

#include <mvcl/core/Error.h>
#include <mvcl/lens/Lens.h>

namespace mvcl {

AnimationPlayer::AnimationPlayer(Animation animation, const LensStack &lenses, const Camera &baseCamera,
                                 const ViewCoordinates &coordinates)
    : m_animation(std::move(animation)), m_lenses(lenses), m_baseCamera(baseCamera), m_coordinates(coordinates) {
    for (const std::shared_ptr<Lens> &lens : m_lenses.lenses()) m_baseStates.push_back(LensState::of(*lens));
    for (const LensTrack &track : m_animation.lensTracks())
        if (track.lens < 0 || track.lens >= m_lenses.size())
            throw Error("animation", "lens " + std::to_string(track.lens) + " is out of range (the stack has " +
                                         std::to_string(m_lenses.size()) + " lenses)");
}

Camera AnimationPlayer::showFrame(int frame) { return showTime(m_animation.frameTime(frame)); }

Camera AnimationPlayer::cameraAt(double seconds) const {
    if (!m_animation.movesCamera()) return m_baseCamera;
    return m_coordinates.cameraFromWorld(
        m_animation.cameraAt(seconds, m_coordinates.worldFromCamera(m_baseCamera)));
}

Camera AnimationPlayer::showTime(double seconds) {
    for (const LensTrack &track : m_animation.lensTracks()) {
        Lens &lens = *m_lenses.lens(track.lens);
        const LensState &base = m_baseStates[std::size_t(track.lens)];
        LensState wanted = LensState::of(lens);
        wanted.region = Animation::regionAt(track, seconds, base.region);
        wanted.enabled = Animation::enabledAt(track, seconds).value_or(base.enabled);
        for (const auto &[name, value] : Animation::propertiesAt(track, seconds, lens.properties()))
            for (auto &[wantedName, text] : wanted.properties)
                if (wantedName == name) text = value.toString();
        // An unchanged lens keeps its snapshot: the view then has nothing to re-trace under it.
        if (wanted == LensState::of(lens)) continue;
        wanted.applyTo(lens);
    }
    return cameraAt(seconds);
}

void AnimationPlayer::restoreLenses() {
    for (const LensTrack &track : m_animation.lensTracks()) {
        Lens &lens = *m_lenses.lens(track.lens);
        if (LensState::of(lens) != m_baseStates[std::size_t(track.lens)])
            m_baseStates[std::size_t(track.lens)].applyTo(lens);
    }
}

} // namespace mvcl
