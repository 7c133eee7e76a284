#include <mvcl/io/Animation.h>

#include <mvcl/core/Error.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mvcl {

namespace {

/// Where `time` falls among the keyframes that give one field: the keyframes before and after
/// it and the eased fraction of the way between them (the same keyframe twice, s = 0, before
/// the first or after the last). `from` is null when no keyframe gives the field.
template <class Keyframe> struct Segment {
    const Keyframe *from = nullptr;
    const Keyframe *to = nullptr;
    double s = 0.0;
};

template <class Keyframe, class Gives>
Segment<Keyframe> segmentAt(const std::vector<Keyframe> &keyframes, double time, Gives gives) {
    Segment<Keyframe> segment;
    for (const Keyframe &keyframe : keyframes) {
        if (!gives(keyframe)) continue;
        if (keyframe.time <= time) {
            segment.from = &keyframe;
            continue;
        }
        if (!segment.from) { // before the field's first keyframe: its value holds
            segment.from = &keyframe;
            segment.to = &keyframe;
            return segment;
        }
        segment.to = &keyframe;
        segment.s = eased(segment.from->easing, (time - segment.from->time) / (keyframe.time - segment.from->time));
        return segment;
    }
    segment.to = segment.from;
    return segment;
}

template <class T> T mixed(const T &from, const T &to, double s) {
    if (s <= 0.0) return from; // a keyframe's value exactly as written
    if (s >= 1.0) return to;
    return T(from + (to - from) * float(s));
}

/// A camera or lens field's value at `time`: `base` when no keyframe gives it.
template <class Keyframe, class Field, class Value>
Value fieldAt(const std::vector<Keyframe> &keyframes, double time, Field field, const Value &base) {
    const Segment<Keyframe> segment = segmentAt(keyframes, time, [&](const Keyframe &k) { return (k.*field).has_value(); });
    if (!segment.from) return base;
    return mixed(*(segment.from->*field), *(segment.to->*field), segment.s);
}

/// `point` turned by `radians` about the line through `center` along the unit `axis` (Rodrigues).
glm::dvec3 rotated(const glm::dvec3 &point, const glm::dvec3 &center, const glm::dvec3 &axis, double radians) {
    const glm::dvec3 v = point - center;
    const double c = std::cos(radians), s = std::sin(radians);
    return center + v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

template <class Keyframe> void insertByTime(std::vector<Keyframe> &keyframes, const Keyframe &keyframe, auto merge) {
    const auto at = std::lower_bound(keyframes.begin(), keyframes.end(), keyframe.time,
                                     [](const Keyframe &k, double time) { return k.time < time; });
    if (at != keyframes.end() && at->time == keyframe.time) merge(*at, keyframe);
    else keyframes.insert(at, keyframe);
}

template <class T> void replaceIfGiven(std::optional<T> &into, const std::optional<T> &from) {
    if (from) into = from;
}

} // namespace

const PropertyValue *LensKeyframe::property(std::string_view name) const {
    for (const auto &[key, value] : properties)
        if (key == name) return &value;
    return nullptr;
}

int Animation::frameCount() const { return std::max(1, int(std::lround(m_duration * m_frameRate))); }

double Animation::frameTime(int frame) const { return double(frame) / m_frameRate; }

void Animation::addCameraKeyframe(const CameraKeyframe &keyframe) {
    insertByTime(m_cameraKeyframes, keyframe, [](CameraKeyframe &into, const CameraKeyframe &from) {
        into.easing = from.easing;
        replaceIfGiven(into.eye, from.eye);
        replaceIfGiven(into.target, from.target);
        replaceIfGiven(into.up, from.up);
        replaceIfGiven(into.verticalFovDegrees, from.verticalFovDegrees);
    });
}

void Animation::addLensKeyframe(int lens, const LensKeyframe &keyframe) {
    auto track = std::ranges::find(m_lensTracks, lens, &LensTrack::lens);
    if (track == m_lensTracks.end()) {
        m_lensTracks.push_back({lens, {}});
        track = m_lensTracks.end() - 1;
    }
    insertByTime(track->keyframes, keyframe, [](LensKeyframe &into, const LensKeyframe &from) {
        into.easing = from.easing;
        for (const auto &[name, value] : from.properties) {
            const auto same = std::ranges::find(into.properties, name, &std::pair<std::string, PropertyValue>::first);
            if (same != into.properties.end()) same->second = value;
            else into.properties.emplace_back(name, value);
        }
        replaceIfGiven(into.enabled, from.enabled);
        replaceIfGiven(into.center, from.center);
        replaceIfGiven(into.size, from.size);
        replaceIfGiven(into.feather, from.feather);
        replaceIfGiven(into.points, from.points);
    });
}

void Animation::addSweep(int lens, const std::string &property, const PropertyValue &from, const PropertyValue &to) {
    LensKeyframe first, last;
    first.properties.emplace_back(property, from);
    last.time = frameTime(frameCount() - 1);
    last.properties.emplace_back(property, to);
    addLensKeyframe(lens, first);
    addLensKeyframe(lens, last);
}

Animation Animation::turntable(int frameCount, double frameRate) {
    Animation animation;
    animation.setFrameRate(frameRate);
    animation.setDuration(double(frameCount) / frameRate);
    animation.setOrbit(CameraOrbit{}); // 0 → 360 degrees over the whole duration: frame N would be frame 0
    return animation;
}

LensStackCamera Animation::cameraAt(double time, const LensStackCamera &base) const {
    LensStackCamera camera = base;
    camera.eye = fieldAt(m_cameraKeyframes, time, &CameraKeyframe::eye, base.eye);
    camera.target = fieldAt(m_cameraKeyframes, time, &CameraKeyframe::target, base.target);
    camera.up = fieldAt(m_cameraKeyframes, time, &CameraKeyframe::up, base.up);
    camera.verticalFovDegrees =
        fieldAt(m_cameraKeyframes, time, &CameraKeyframe::verticalFovDegrees, base.verticalFovDegrees);
    if (!m_orbit) return camera;
    const CameraOrbit &orbit = *m_orbit;
    const double end = orbit.endTime.value_or(m_duration);
    const double fraction = end > orbit.startTime ? (time - orbit.startTime) / (end - orbit.startTime)
                                                  : (time >= end ? 1.0 : 0.0);
    const double degrees = orbit.fromDegrees + (orbit.toDegrees - orbit.fromDegrees) * eased(orbit.easing, fraction);
    const glm::dvec3 axis = glm::normalize(glm::dvec3(orbit.axis.value_or(camera.up)));
    const glm::dvec3 center(orbit.center.value_or(camera.target));
    const double radians = degrees * (3.14159265358979323846 / 180.0);
    camera.eye = glm::vec3(rotated(glm::dvec3(camera.eye), center, axis, radians));
    camera.target = glm::vec3(rotated(glm::dvec3(camera.target), center, axis, radians));
    camera.up = glm::vec3(rotated(glm::dvec3(camera.up), glm::dvec3(0.0), axis, radians));
    return camera;
}

std::vector<std::pair<std::string, PropertyValue>> Animation::propertiesAt(const LensTrack &track, double time,
                                                                           const PropertyTable &table) {
    std::vector<std::pair<std::string, PropertyValue>> values;
    for (const PropertyDecl &decl : table) {
        const Segment<LensKeyframe> segment =
            segmentAt(track.keyframes, time, [&](const LensKeyframe &k) { return k.property(decl.name) != nullptr; });
        if (!segment.from) continue;
        values.emplace_back(decl.name, interpolateProperty(decl, *segment.from->property(decl.name),
                                                           *segment.to->property(decl.name), segment.s));
    }
    return values;
}

LensRegion Animation::regionAt(const LensTrack &track, double time, const LensRegion &base) {
    LensRegion region = base;
    const std::vector<LensKeyframe> &keys = track.keyframes;
    if (base.shape() == LensRegion::Shape::Polygon) {
        const Segment<LensKeyframe> segment =
            segmentAt(keys, time, [](const LensKeyframe &k) { return k.points.has_value(); });
        if (segment.from) {
            std::vector<glm::vec2> points = *segment.from->points;
            for (std::size_t i = 0; i < points.size(); ++i)
                points[i] = mixed(points[i], (*segment.to->points)[i], segment.s);
            region = LensRegion::polygon(std::move(points));
            region.setOutlineWidth(base.outlineWidth());
            region.setOutlineColor(base.outlineColor());
        }
    } else {
        region.setSize(fieldAt(keys, time, &LensKeyframe::size, base.size()));
    }
    region.setCenter(fieldAt(keys, time, &LensKeyframe::center, region.center()));
    region.setFeather(fieldAt(keys, time, &LensKeyframe::feather, base.feather()));
    return region;
}

std::optional<bool> Animation::enabledAt(const LensTrack &track, double time) {
    // Steps: the last keyframe at or before `time` that gives one (before the first, the first).
    const Segment<LensKeyframe> segment =
        segmentAt(track.keyframes, time, [](const LensKeyframe &k) { return k.enabled.has_value(); });
    if (!segment.from) return std::nullopt;
    return segment.from->enabled;
}

} // namespace mvcl
