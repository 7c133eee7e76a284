// The animation model: frame times, tracks per keyed value, camera keyframes and orbits, lens
// properties, regions and enabled flags between keyframes.

#include <mvcl/io/Animation.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

using namespace mvcl;

namespace {

LensStackCamera baseCamera() { return LensStackCamera{"", {0.f, 1.f, 10.f}, {0.f, 1.f, 0.f}, {0.f, 1.f, 0.f}, 40.f}; }

PropertyTable layerTable() {
    return {PropertyDecl::real("distance", 0.0, 0.0, 100.0, "", "d"),
            PropertyDecl::choice("mode", "on", {"on", "off"}, "a choice")};
}

} // namespace

TEST(Animation, FramesShowEvenTimesAndNeverRepeatTheEnd) {
    Animation animation;
    animation.setDuration(2.0);
    animation.setFrameRate(24.0);
    EXPECT_EQ(animation.frameCount(), 48);
    EXPECT_DOUBLE_EQ(animation.frameTime(47), 47.0 / 24.0);
    animation.setDuration(0.001);
    EXPECT_EQ(animation.frameCount(), 1);
}

TEST(Animation, TurntableTurnsOnceAndItsLastFrameIsOneStepBeforeTheFirst) {
    const Animation turntable = Animation::turntable(8, 30.0);
    EXPECT_EQ(turntable.frameCount(), 8);
    const LensStackCamera base = baseCamera();
    const LensStackCamera first = turntable.cameraAt(turntable.frameTime(0), base);
    EXPECT_EQ(first.eye, base.eye); // a turn by 0 leaves the camera as it is, bit for bit
    EXPECT_EQ(first.target, base.target);
    const LensStackCamera last = turntable.cameraAt(turntable.frameTime(7), base);
    // One step (45 degrees) short of a full turn about the up axis through the target.
    const float step = glm::radians(45.f);
    const glm::vec3 expected(-10.f * std::sin(step), 1.f, 10.f * std::cos(step));
    EXPECT_NEAR(glm::distance(last.eye, expected), 0.f, 1e-5f) << last.eye.x << " " << last.eye.z;
    EXPECT_NEAR(glm::distance(turntable.cameraAt(turntable.duration(), base).eye, base.eye), 0.f, 1e-5f);
    EXPECT_EQ(last.target, base.target);
}

TEST(Animation, CameraFieldsAreTracksOfTheirOwn) {
    Animation animation;
    animation.setDuration(2.0);
    CameraKeyframe start;
    start.eye = glm::vec3(0.f, 1.f, 10.f);
    start.verticalFovDegrees = 40.f;
    CameraKeyframe middle;
    middle.time = 1.0;
    middle.verticalFovDegrees = 20.f;
    CameraKeyframe end;
    end.time = 2.0;
    end.eye = glm::vec3(0.f, 1.f, 2.f);
    animation.addCameraKeyframe(end); // out of order on purpose: kept sorted
    animation.addCameraKeyframe(start);
    animation.addCameraKeyframe(middle);
    ASSERT_EQ(animation.cameraKeyframes().size(), 3u);
    EXPECT_EQ(animation.cameraKeyframes()[1].time, 1.0);
    const LensStackCamera at = animation.cameraAt(0.5, baseCamera());
    EXPECT_FLOAT_EQ(at.eye.z, 8.f);                // between 0 s and 2 s: a quarter of the way
    EXPECT_FLOAT_EQ(at.verticalFovDegrees, 30.f);  // between 0 s and 1 s: half way
    EXPECT_EQ(at.target, baseCamera().target);     // not keyed: the base's
    EXPECT_FLOAT_EQ(animation.cameraAt(1.5, baseCamera()).verticalFovDegrees, 20.f); // after its last key
}

TEST(Animation, OrbitAboutAGivenAxisAndCentreOverPartOfTheDuration) {
    Animation animation;
    animation.setDuration(4.0);
    CameraOrbit orbit;
    orbit.axis = glm::vec3(0.f, 2.f, 0.f); // any length
    orbit.center = glm::vec3(0.f);
    orbit.fromDegrees = 0.0;
    orbit.toDegrees = 90.0;
    orbit.startTime = 1.0;
    orbit.endTime = 3.0;
    animation.setOrbit(orbit);
    const LensStackCamera base{"", {0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f};
    EXPECT_EQ(animation.cameraAt(0.5, base).eye, base.eye);
    const glm::vec3 quarter = animation.cameraAt(3.5, base).eye; // held at 90 degrees: +z turns to +x
    EXPECT_NEAR(quarter.x, 5.f, 1e-5f);
    EXPECT_NEAR(quarter.z, 0.f, 1e-5f);
    const glm::vec3 eighth = animation.cameraAt(2.0, base).eye;
    EXPECT_NEAR(eighth.x, 5.f * std::sqrt(0.5f), 1e-5f);
}

TEST(Animation, LensPropertiesInterpolateByTypeWithTheEarlierKeyframesEasing) {
    LensTrack track;
    LensKeyframe a;
    a.easing = Easing::SmoothStep;
    a.properties = {{"distance", PropertyValue::real(0.0)}, {"mode", PropertyValue::choice("on")}};
    LensKeyframe b;
    b.time = 1.0;
    b.properties = {{"distance", PropertyValue::real(4.0)}, {"mode", PropertyValue::choice("off")}};
    track.keyframes = {a, b};
    const auto at = Animation::propertiesAt(track, 0.25, layerTable());
    ASSERT_EQ(at.size(), 2u);
    EXPECT_EQ(at[0].first, "distance");
    EXPECT_DOUBLE_EQ(at[0].second.toReal(), 4.0 * 0.15625);
    EXPECT_EQ(at[1].second.toChoice(), "on");
    EXPECT_EQ(Animation::propertiesAt(track, 1.0, layerTable())[1].second.toChoice(), "off");
    EXPECT_DOUBLE_EQ(Animation::propertiesAt(track, 0.0, layerTable())[0].second.toReal(), 0.0);
}

TEST(Animation, PropertiesNoKeyframeGivesAreLeftOut) {
    LensTrack track;
    LensKeyframe a;
    a.properties = {{"distance", PropertyValue::real(2.0)}};
    track.keyframes = {a};
    const auto at = Animation::propertiesAt(track, 0.5, layerTable());
    ASSERT_EQ(at.size(), 1u);
    EXPECT_DOUBLE_EQ(at[0].second.toReal(), 2.0);
}

TEST(Animation, RegionsAndEnabledFlagsBetweenKeyframes) {
    LensTrack track;
    LensKeyframe a;
    a.center = glm::vec2(0.2f, 0.5f);
    a.enabled = false;
    LensKeyframe b;
    b.time = 2.0;
    b.center = glm::vec2(0.8f, 0.5f);
    b.size = glm::vec2(0.2f);
    b.enabled = true;
    track.keyframes = {a, b};
    LensRegion base = LensRegion::ellipse({0.5f, 0.5f}, {0.4f, 0.4f});
    base.setFeather(3.f);
    const LensRegion half = Animation::regionAt(track, 1.0, base);
    EXPECT_FLOAT_EQ(half.center().x, 0.5f);
    EXPECT_FLOAT_EQ(half.size().x, 0.2f); // only one keyframe gives a size: it holds
    EXPECT_FLOAT_EQ(half.feather(), 3.f);
    EXPECT_EQ(half.shape(), LensRegion::Shape::Ellipse);
    EXPECT_EQ(Animation::enabledAt(track, 1.9), false);
    EXPECT_EQ(Animation::enabledAt(track, 2.0), true);
    EXPECT_FALSE(Animation::enabledAt(LensTrack{}, 1.0));
}

TEST(Animation, PolygonPointsMoveTogether) {
    LensTrack track;
    LensKeyframe a, b;
    a.points = std::vector<glm::vec2>{{0.f, 0.f}, {0.4f, 0.f}, {0.f, 0.4f}};
    b.time = 1.0;
    b.points = std::vector<glm::vec2>{{0.2f, 0.2f}, {0.6f, 0.2f}, {0.2f, 0.6f}};
    track.keyframes = {a, b};
    LensRegion base = LensRegion::polygon({{0.f, 0.f}, {1.f, 0.f}, {0.f, 1.f}});
    base.setOutlineWidth(2.f);
    const LensRegion half = Animation::regionAt(track, 0.5, base);
    ASSERT_EQ(half.points().size(), 3u);
    EXPECT_FLOAT_EQ(half.points()[1].x, 0.5f);
    EXPECT_FLOAT_EQ(half.points()[1].y, 0.1f);
    EXPECT_FLOAT_EQ(half.outlineWidth(), 2.f);
}

TEST(Animation, SweepsReachTheirEndOnTheLastFrame) {
    Animation animation;
    animation.setFrameRate(30.0);
    animation.setDuration(5.0 / 30.0);
    animation.addSweep(0, "distance", PropertyValue::real(0.0), PropertyValue::real(4.0));
    ASSERT_EQ(animation.lensTracks().size(), 1u);
    const LensTrack &track = animation.lensTracks().front();
    for (int frame = 0; frame < 5; ++frame)
        EXPECT_NEAR(Animation::propertiesAt(track, animation.frameTime(frame), layerTable())[0].second.toReal(),
                    double(frame), 1e-12);
    EXPECT_EQ(Animation::propertiesAt(track, animation.frameTime(4), layerTable())[0].second.toReal(), 4.0);
}

TEST(Animation, AKeyframeAtAnExistingTimeReplacesTheValuesItGives) {
    Animation animation;
    LensKeyframe a;
    a.properties = {{"distance", PropertyValue::real(1.0)}};
    a.center = glm::vec2(0.1f);
    LensKeyframe again;
    again.properties = {{"distance", PropertyValue::real(2.0)}, {"mode", PropertyValue::choice("off")}};
    animation.addLensKeyframe(1, a);
    animation.addLensKeyframe(1, again);
    ASSERT_EQ(animation.lensTracks().size(), 1u);
    const LensKeyframe &merged = animation.lensTracks().front().keyframes.at(0);
    EXPECT_EQ(merged.property("distance")->toReal(), 2.0);
    EXPECT_EQ(merged.property("mode")->toChoice(), "off");
    EXPECT_TRUE(merged.center.has_value());
}
