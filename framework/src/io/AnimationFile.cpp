#include <mvcl/io/AnimationFile.h>

#include "JsonFile_p.h"

#include <mvcl/core/Error.h>
#include <mvcl/lens/Lens.h>

#include <algorithm>
#include <cmath>

namespace mvcl {

namespace {

using namespace detail; // the JSON file helpers

constexpr int kFileVersion = 1;

/// Times and rates in double: a float would move a keyframe at 0.1 s off its frame.
double readReal(const Json &value, const JsonLocation &where) {
    if (!value.is_number()) where.fail("expected a number, got " + value.dump());
    const double number = value.get<double>();
    if (!std::isfinite(number)) where.fail("number " + value.dump() + " is out of range");
    return number;
}

double readTimeValue(const Json &value, double duration, const JsonLocation &where) {
    const double time = readReal(value, where);
    if (time < 0.0 || time > duration)
        where.fail("time " + value.dump() + " is outside the duration (0 to " + Json(duration).dump() + " s)");
    return time;
}

double readTime(const Json &keyframe, double duration, const JsonLocation &where) {
    if (!keyframe.contains("time")) where.fail("missing \"time\" (seconds)");
    return readTimeValue(keyframe["time"], duration, where.key("time"));
}

Easing readEasing(const Json &object, const JsonLocation &where) {
    if (!object.contains("easing")) return Easing::Linear;
    const std::string name = readString(object["easing"], where.key("easing"));
    const std::optional<Easing> easing = easingNamed(name);
    if (!easing) where.key("easing").fail("unknown easing '" + name + "' (known: linear, smooth)");
    return *easing;
}

/// Keyframes of one list must come in time order, each at its own time.
void checkTimeOrder(double previous, double time, const JsonLocation &where) {
    if (time <= previous)
        where.key("time").fail("keyframes must be in time order, each at its own time (" + Json(time).dump() +
                               " comes after " + Json(previous).dump() + ")");
}

const Json &readArray(const Json &object, const char *key, const JsonLocation &where, const char *what) {
    const Json &array = object[key];
    if (!array.is_array()) where.key(key).fail(std::string("expected an array of ") + what);
    return array;
}

glm::vec3 readDirection(const Json &value, const JsonLocation &where) {
    const glm::vec3 direction = readVector<3>(value, where);
    if (direction == glm::vec3(0.f)) where.fail("must not be zero");
    return direction;
}

CameraKeyframe readCameraKeyframe(const Json &json, double duration, const JsonLocation &where) {
    static constexpr std::string_view kKeys[] = {"time", "easing", "eye", "target", "up", "fov"};
    expectObject(json, where);
    rejectUnknownKeys(json, kKeys, where);
    CameraKeyframe keyframe;
    keyframe.time = readTime(json, duration, where);
    keyframe.easing = readEasing(json, where);
    if (json.contains("eye")) keyframe.eye = readVector<3>(json["eye"], where.key("eye"));
    if (json.contains("target")) keyframe.target = readVector<3>(json["target"], where.key("target"));
    if (json.contains("up")) keyframe.up = readDirection(json["up"], where.key("up"));
    if (json.contains("fov")) {
        keyframe.verticalFovDegrees = readNumber(json["fov"], where.key("fov"));
        if (!(*keyframe.verticalFovDegrees > 0.f && *keyframe.verticalFovDegrees < 180.f))
            where.key("fov").fail("must be in (0, 180) degrees");
    }
    if (keyframe.eye && keyframe.target && *keyframe.eye == *keyframe.target)
        where.fail("eye and target are the same point");
    return keyframe;
}

CameraOrbit readOrbit(const Json &json, double duration, const JsonLocation &where) {
    static constexpr std::string_view kKeys[] = {"axis", "center", "angles", "start", "end", "easing"};
    expectObject(json, where);
    rejectUnknownKeys(json, kKeys, where);
    CameraOrbit orbit;
    if (json.contains("axis")) orbit.axis = readDirection(json["axis"], where.key("axis"));
    if (json.contains("center")) orbit.center = readVector<3>(json["center"], where.key("center"));
    if (json.contains("angles")) {
        const JsonLocation anglesWhere = where.key("angles");
        const Json &angles = json["angles"];
        if (!angles.is_array() || angles.size() != 2)
            anglesWhere.fail("expected [from, to] in degrees, got " + angles.dump());
        orbit.fromDegrees = readReal(angles[0], anglesWhere.index(0));
        orbit.toDegrees = readReal(angles[1], anglesWhere.index(1));
    }
    if (json.contains("start")) orbit.startTime = readTimeValue(json["start"], duration, where.key("start"));
    if (json.contains("end")) orbit.endTime = readTimeValue(json["end"], duration, where.key("end"));
    if (orbit.endTime && *orbit.endTime <= orbit.startTime) where.key("end").fail("must come after \"start\"");
    orbit.easing = readEasing(json, where);
    return orbit;
}

/// The lens a track names: an index into the stack or a label only one lens has.
int readLensReference(const Json &value, const LensStack &lenses, const JsonLocation &where) {
    const int count = lenses.size();
    if (value.is_number_integer()) {
        const long long index = value.get<long long>();
        if (index < 0 || index >= count)
            where.fail("lens " + value.dump() + " is out of range (the session has " + std::to_string(count) +
                       (count == 1 ? " lens" : " lenses") + ", 0 = bottom)");
        return int(index);
    }
    const std::string label = readString(value, where);
    int found = -1;
    std::string labels;
    for (int i = 0; i < count; ++i) {
        const std::string &other = lenses.lens(i)->label();
        labels.append(labels.empty() ? "" : ", ").append("'" + other + "'");
        if (other != label) continue;
        if (found >= 0)
            where.fail("lenses " + std::to_string(found) + " and " + std::to_string(i) + " are both labelled '" +
                       label + "': name one by its index");
        found = i;
    }
    if (found < 0)
        where.fail("no lens of the session is labelled '" + label + "' (labels: " +
                   (labels.empty() ? std::string("none, the session has no lenses") : labels) + ")");
    return found;
}

void readRegionKeys(const Json &json, const Lens &lens, LensKeyframe &keyframe, const JsonLocation &where) {
    static constexpr std::string_view kKeys[] = {"center", "size", "feather", "points"};
    expectObject(json, where);
    rejectUnknownKeys(json, kKeys, where);
    const LensRegion &region = lens.snapshot()->region;
    const bool polygon = region.shape() == LensRegion::Shape::Polygon;
    if (json.contains("center")) keyframe.center = readVector<2>(json["center"], where.key("center"));
    if (json.contains("size")) {
        if (polygon) where.key("size").fail("a polygon lens is shaped by its \"points\"");
        keyframe.size = readVector<2>(json["size"], where.key("size"));
        if (keyframe.size->x < 0.f || keyframe.size->y < 0.f) where.key("size").fail("must not be negative");
    }
    if (json.contains("feather")) {
        keyframe.feather = readNumber(json["feather"], where.key("feather"));
        if (*keyframe.feather < 0.f) where.key("feather").fail("must not be negative");
    }
    if (json.contains("points")) {
        const JsonLocation pointsWhere = where.key("points");
        if (!polygon) pointsWhere.fail("only a polygon lens has points");
        const Json &points = json["points"];
        if (!points.is_array() || points.size() != region.points().size())
            pointsWhere.fail("expected " + std::to_string(region.points().size()) +
                             " [x, y] points, as many as the lens has");
        keyframe.points.emplace();
        for (std::size_t i = 0; i < points.size(); ++i)
            keyframe.points->push_back(readVector<2>(points[i], pointsWhere.index(i)));
    }
}

LensKeyframe readLensKeyframe(const Json &json, const Lens &lens, double duration, const JsonLocation &where) {
    static constexpr std::string_view kKeys[] = {"time", "easing", "enabled", "region", "properties"};
    expectObject(json, where);
    rejectUnknownKeys(json, kKeys, where);
    LensKeyframe keyframe;
    keyframe.time = readTime(json, duration, where);
    keyframe.easing = readEasing(json, where);
    if (json.contains("enabled")) keyframe.enabled = readBool(json["enabled"], where.key("enabled"));
    if (json.contains("region")) readRegionKeys(json["region"], lens, keyframe, where.key("region"));
    if (json.contains("properties")) {
        const JsonLocation propertiesWhere = where.key("properties");
        for (const auto &[name, value] : expectObject(json["properties"], propertiesWhere).items()) {
            const PropertyDecl *decl = findProperty(lens.properties(), name);
            if (!decl) propertiesWhere.fail(unknownPropertyMessage(name, lens));
            const JsonLocation valueWhere = propertiesWhere.key(name);
            try {
                keyframe.properties.emplace_back(name, decl->parse(propertyText(value, valueWhere)));
            } catch (const Error &e) { // out of range, wrong type: the declaration says which
                valueWhere.fail(e.problem());
            }
        }
    }
    return keyframe;
}

Animation readAnimation(const Json &document, const LensStack &lenses, const JsonLocation &where) {
    static constexpr std::string_view kTopKeys[] = {"version", "duration", "frameRate", "camera", "lenses"};
    expectObject(document, where);
    rejectUnknownKeys(document, kTopKeys, where);
    expectVersion(document, kFileVersion, where);
    Animation animation;
    if (!document.contains("duration")) where.fail("missing \"duration\" (seconds)");
    const double duration = readReal(document["duration"], where.key("duration"));
    if (!(duration > 0.0)) where.key("duration").fail("must be more than 0 seconds");
    animation.setDuration(duration);
    if (document.contains("frameRate")) {
        const double rate = readReal(document["frameRate"], where.key("frameRate"));
        if (!(rate > 0.0 && rate <= 1000.0)) where.key("frameRate").fail("must be in (0, 1000] frames per second");
        animation.setFrameRate(rate);
    }
    if (document.contains("camera")) {
        static constexpr std::string_view kCameraKeys[] = {"keyframes", "orbit"};
        const JsonLocation cameraWhere = where.key("camera");
        const Json &camera = expectObject(document["camera"], cameraWhere);
        rejectUnknownKeys(camera, kCameraKeys, cameraWhere);
        if (camera.contains("keyframes")) {
            const Json &keyframes = readArray(camera, "keyframes", cameraWhere, "camera keyframes");
            for (std::size_t i = 0; i < keyframes.size(); ++i) {
                const JsonLocation keyWhere = cameraWhere.key("keyframes").index(i);
                const CameraKeyframe keyframe = readCameraKeyframe(keyframes[i], duration, keyWhere);
                if (i > 0) checkTimeOrder(animation.cameraKeyframes().back().time, keyframe.time, keyWhere);
                animation.addCameraKeyframe(keyframe);
            }
        }
        if (camera.contains("orbit")) animation.setOrbit(readOrbit(camera["orbit"], duration, cameraWhere.key("orbit")));
    }
    if (document.contains("lenses")) {
        const JsonLocation lensesWhere = where.key("lenses");
        const Json &tracks = readArray(document, "lenses", where, "lens tracks");
        std::vector<int> seen;
        for (std::size_t t = 0; t < tracks.size(); ++t) {
            static constexpr std::string_view kTrackKeys[] = {"lens", "keyframes"};
            const JsonLocation trackWhere = lensesWhere.index(t);
            const Json &track = expectObject(tracks[t], trackWhere);
            rejectUnknownKeys(track, kTrackKeys, trackWhere);
            if (!track.contains("lens")) trackWhere.fail("missing \"lens\" (a label or an index, 0 = bottom)");
            const int lens = readLensReference(track["lens"], lenses, trackWhere.key("lens"));
            if (std::ranges::find(seen, lens) != seen.end())
                trackWhere.key("lens").fail("lens " + std::to_string(lens) + " has a track already");
            seen.push_back(lens);
            if (!track.contains("keyframes")) continue;
            const Json &keyframes = readArray(track, "keyframes", trackWhere, "keyframes");
            for (std::size_t i = 0; i < keyframes.size(); ++i) {
                const JsonLocation keyWhere = trackWhere.key("keyframes").index(i);
                const LensKeyframe keyframe = readLensKeyframe(keyframes[i], *lenses.lens(lens), duration, keyWhere);
                if (i > 0) checkTimeOrder(animation.lensTracks().back().keyframes.back().time, keyframe.time, keyWhere);
                animation.addLensKeyframe(lens, keyframe);
            }
        }
    }
    return animation;
}

Json easingJson(Easing easing) { return easingName(easing); }

Json cameraJson(const Animation &animation) {
    Json camera = Json::object();
    if (!animation.cameraKeyframes().empty()) {
        Json keyframes = Json::array();
        for (const CameraKeyframe &k : animation.cameraKeyframes()) {
            Json json{{"time", k.time}, {"easing", easingJson(k.easing)}};
            if (k.eye) json["eye"] = vectorJson(*k.eye);
            if (k.target) json["target"] = vectorJson(*k.target);
            if (k.up) json["up"] = vectorJson(*k.up);
            if (k.verticalFovDegrees) json["fov"] = shortestDouble(*k.verticalFovDegrees);
            keyframes.push_back(std::move(json));
        }
        camera["keyframes"] = std::move(keyframes);
    }
    if (const std::optional<CameraOrbit> &orbit = animation.orbit()) {
        Json json = Json::object();
        if (orbit->axis) json["axis"] = vectorJson(*orbit->axis);
        if (orbit->center) json["center"] = vectorJson(*orbit->center);
        json["angles"] = {orbit->fromDegrees, orbit->toDegrees};
        json["start"] = orbit->startTime;
        if (orbit->endTime) json["end"] = *orbit->endTime;
        json["easing"] = easingJson(orbit->easing);
        camera["orbit"] = std::move(json);
    }
    return camera;
}

Json lensReferenceJson(int lens, const LensStack &lenses) {
    const std::string &label = lenses.lens(lens)->label();
    const auto sameLabel = [&](const std::shared_ptr<Lens> &other) { return other->label() == label; };
    if (!label.empty() && std::ranges::count_if(lenses.lenses(), sameLabel) == 1) return label;
    return lens;
}

Json lensKeyframeJson(const LensKeyframe &k) {
    Json json{{"time", k.time}, {"easing", easingJson(k.easing)}};
    if (k.enabled) json["enabled"] = *k.enabled;
    Json region = Json::object();
    if (k.center) region["center"] = vectorJson(*k.center);
    if (k.size) region["size"] = vectorJson(*k.size);
    if (k.feather) region["feather"] = shortestDouble(*k.feather);
    if (k.points) {
        Json points = Json::array();
        for (const glm::vec2 &point : *k.points) points.push_back(vectorJson(point));
        region["points"] = std::move(points);
    }
    if (!region.empty()) json["region"] = std::move(region);
    if (!k.properties.empty()) {
        Json properties = Json::object();
        for (const auto &[name, value] : k.properties) properties[name] = value.toString();
        json["properties"] = std::move(properties);
    }
    return json;
}

} // namespace

Animation parseAnimationJson(std::string_view text, const std::string &sourceName, const LensStack &lenses) {
    return readAnimation(parseJsonDocument(text, sourceName), lenses, JsonLocation{sourceName, "", false});
}

Animation readAnimationFile(const std::filesystem::path &path, const LensStack &lenses) {
    return parseAnimationJson(readTextFile(path, "animation file"), path.string(), lenses);
}

std::string animationJson(const Animation &animation, const LensStack &lenses) {
    Json json{{"version", kFileVersion}, {"duration", animation.duration()}, {"frameRate", animation.frameRate()}};
    if (Json camera = cameraJson(animation); !camera.empty()) json["camera"] = std::move(camera);
    Json tracks = Json::array();
    for (const LensTrack &track : animation.lensTracks()) {
        Json keyframes = Json::array();
        for (const LensKeyframe &keyframe : track.keyframes) keyframes.push_back(lensKeyframeJson(keyframe));
        tracks.push_back({{"lens", lensReferenceJson(track.lens, lenses)}, {"keyframes", std::move(keyframes)}});
    }
    if (!tracks.empty()) json["lenses"] = std::move(tracks);
    try {
        return prettyJson(json) + "\n";
    } catch (const Json::exception &e) { // e.g. a label that is not valid UTF-8
        throw Error("animation file", e.what());
    }
}

void addSweepSpec(Animation &animation, std::string_view spec, const LensStack &lenses) {
    std::string quoted(1, '\'');
    quoted.append(spec).push_back('\'');
    const JsonLocation where{"--sweep", quoted, true};
    const std::size_t equals = spec.find('=');
    const std::size_t colon = spec.find(':', equals == std::string_view::npos ? 0 : equals);
    const std::size_t dot = spec.substr(0, equals).rfind('.');
    if (equals == std::string_view::npos || colon == std::string_view::npos || dot == std::string_view::npos ||
        spec.find(':', colon + 1) != std::string_view::npos)
        where.fail("expected LENS.PROPERTY=FROM:TO, LENS a label or an index (e.g. reveal.distance=0:4)");
    const std::string reference(spec.substr(0, dot));
    const bool isIndex = !reference.empty() && std::ranges::all_of(reference, [](char c) { return c >= '0' && c <= '9'; });
    const int lens = readLensReference(isIndex ? Json(std::stoll(reference)) : Json(reference), lenses, where);
    const std::string name(spec.substr(dot + 1, equals - dot - 1));
    const Lens &target = *lenses.lens(lens);
    const PropertyDecl *decl = findProperty(target.properties(), name);
    if (!decl) where.fail(unknownPropertyMessage(name, target));
    try {
        animation.addSweep(lens, name, decl->parse(spec.substr(equals + 1, colon - equals - 1)),
                           decl->parse(spec.substr(colon + 1)));
    } catch (const Error &e) {
        where.fail(e.what()); // names the property: "distance: ..."
    }
}

void writeAnimationFile(const std::filesystem::path &path, const Animation &animation, const LensStack &lenses) {
    std::string text;
    try {
        text = animationJson(animation, lenses);
    } catch (const Error &e) {
        throw Error(path.string(), e.problem());
    }
    writeFileAtomically(path, text);
}

} // namespace mvcl
