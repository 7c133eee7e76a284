// Animation files read against a lens stack: the format, errors that name the file and the JSON
// path, round trips, and --sweep specs.

#include <mvcl/io/AnimationFile.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/io/LensStackFile.h>
#include <mvcl/lens/LensRegistry.h>

#include "lens/InTreeLensRegistry.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace mvcl;
using test::errorOf;

namespace {

const LensRegistry &registry() {
    EXPECT_TRUE(test::inTreeLenses().loadErrors.empty()) << test::inTreeLenses().loadErrors.front().what();
    return test::inTreeLenses().registry;
}

/// Layer lens "reveal" (ellipse), achromatic "grey", shadow "tinted" (polygon).
LensStack threeLenses() {
    return parseLensStackJson(R"({"lenses": [
        {"type": "layer", "label": "reveal", "region": {"shape": "ellipse", "center": [0.5, 0.5], "size": [0.4, 0.4]}},
        {"type": "achromatic", "label": "grey"},
        {"type": "shadow", "label": "tinted", "region": {"points": [[0, 0], [0.5, 0], [0, 0.5]]}}]})",
                              "stack.json", registry())
        .lenses;
}

Animation parsed(const std::string &text) { return parseAnimationJson(text, "anim.json", threeLenses()); }

std::string errorIn(const std::string &text) {
    return errorOf([&] { parsed(text); });
}

} // namespace

TEST(AnimationFile, ReadsCameraOrbitAndLensTracksByLabelOrIndex) {
    const Animation animation = parsed(R"({
        "version": 1, "duration": 2, "frameRate": 12,
        "camera": {"keyframes": [{"time": 0, "eye": [0, 1, 10], "fov": 40, "easing": "smooth"},
                                 {"time": 2, "target": [0, 0.5, 0], "up": [0, 1, 0]}],
                   "orbit": {"axis": [0, 1, 0], "angles": [0, 180], "start": 0.5, "end": 1.5}},
        "lenses": [{"lens": "reveal", "keyframes": [
                        {"time": 0, "properties": {"distance": 0, "layers": "1-"}, "region": {"center": [0.2, 0.5]}},
                        {"time": 2, "properties": {"distance": 3.5}, "region": {"size": [0.1, 0.1], "feather": 4}}]},
                   {"lens": 2, "keyframes": [{"time": 1, "enabled": false,
                                              "properties": {"tint": [1, 0, 0], "mode": "tinted"},
                                              "region": {"points": [[0, 0], [1, 0], [0, 1]]}}]}]})");
    EXPECT_DOUBLE_EQ(animation.duration(), 2.0);
    EXPECT_DOUBLE_EQ(animation.frameRate(), 12.0);
    EXPECT_EQ(animation.frameCount(), 24);
    ASSERT_EQ(animation.cameraKeyframes().size(), 2u);
    EXPECT_EQ(animation.cameraKeyframes()[0].easing, Easing::SmoothStep);
    EXPECT_EQ(*animation.cameraKeyframes()[0].verticalFovDegrees, 40.f);
    EXPECT_FALSE(animation.cameraKeyframes()[1].eye);
    ASSERT_TRUE(animation.orbit());
    EXPECT_EQ(animation.orbit()->toDegrees, 180.0);
    EXPECT_EQ(*animation.orbit()->endTime, 1.5);
    ASSERT_EQ(animation.lensTracks().size(), 2u);
    EXPECT_EQ(animation.lensTracks()[0].lens, 0);
    EXPECT_EQ(animation.lensTracks()[1].lens, 2);
    const LensKeyframe &last = animation.lensTracks()[0].keyframes.at(1);
    EXPECT_EQ(last.property("distance")->toReal(), 3.5);
    EXPECT_EQ(*last.feather, 4.f);
    EXPECT_EQ(animation.lensTracks()[1].keyframes.at(0).property("mode")->toChoice(), "tinted");
}

TEST(AnimationFile, WritesWhatItReads) {
    const LensStack lenses = threeLenses();
    const Animation animation = parsed(R"({"duration": 1.5, "frameRate": 25,
        "camera": {"keyframes": [{"time": 0.1, "eye": [1, 2, 3], "easing": "smooth"}], "orbit": {"angles": [-10, 20]}},
        "lenses": [{"lens": "grey", "keyframes": [{"time": 0, "properties": {"amount": 0.25}},
                                                  {"time": 1.5, "properties": {"amount": 1}, "enabled": true}]}]})");
    const std::string text = animationJson(animation, lenses);
    const Animation again = parseAnimationJson(text, "written.json", lenses);
    EXPECT_EQ(animationJson(again, lenses), text);
    EXPECT_NE(text.find("\"lens\": \"grey\""), std::string::npos) << text;
    EXPECT_EQ(again.lensTracks().at(0).keyframes.at(0).property("amount")->toReal(), 0.25);
    EXPECT_EQ(again.cameraKeyframes().at(0).time, 0.1);

    const fs::path file = fs::temp_directory_path() / "mvcl-animation-file-test" / "written.json";
    fs::remove_all(file.parent_path());
    writeAnimationFile(file, animation, lenses);
    EXPECT_EQ(animationJson(readAnimationFile(file, lenses), lenses), text);
}

TEST(AnimationFile, ErrorsNameTheFileAndTheJsonPath) {
    const struct {
        const char *text;
        const char *message;
    } cases[] = {
        {R"({"duration": 1, "lenses": [{"lens": 0, "keyframes": [{"time": 0, "properties": {"distnce": 1}}]}]})",
         "anim.json: lenses[0].keyframes[0].properties: unknown property 'distnce' of lens 'layer' (known: layers, "
         "distance, rays)"},
        {R"({"duration": 1, "lenses": [{"lens": "grey", "keyframes": [{"time": 0, "properties": {"amount": 2}}]}]})",
         "anim.json: lenses[0].keyframes[0].properties.amount: "},
        {R"({"duration": 1, "lenses": [{"lens": 0, "keyframes": [{"time": 1.5}]}]})",
         "anim.json: lenses[0].keyframes[0].time: time 1.5 is outside the duration (0 to 1.0 s)"},
        {R"({"duration": 1, "camera": {"keyframes": [{"time": -0.5}]}})",
         "anim.json: camera.keyframes[0].time: time -0.5 is outside the duration"},
        {R"({"duration": 2, "lenses": [{"lens": 0, "keyframes": [{"time": 1}, {"time": 0.5}]}]})",
         "anim.json: lenses[0].keyframes[1].time: keyframes must be in time order"},
        {R"({"duration": 1, "lenses": [{"lens": 3}]})",
         "anim.json: lenses[0].lens: lens 3 is out of range (the session has 3 lenses, 0 = bottom)"},
        {R"({"duration": 1, "lenses": [{"lens": "skin"}]})",
         "anim.json: lenses[0].lens: no lens of the session is labelled 'skin' (labels: 'reveal', 'grey', 'tinted')"},
        {R"({"duration": 1, "lenses": [{"lens": 0}, {"lens": "reveal"}]})",
         "anim.json: lenses[1].lens: lens 0 has a track already"},
        {R"({"duration": 1, "camera": {"keyframes": [{"time": 0, "fov": 0}]}})",
         "anim.json: camera.keyframes[0].fov: must be in (0, 180) degrees"},
        {R"({"duration": 1, "camera": {"orbit": {"axis": [0, 0, 0]}}})", "anim.json: camera.orbit.axis: must not be zero"},
        {R"({"duration": 1, "camera": {"orbit": {"start": 0.5, "end": 0.5}}})",
         "anim.json: camera.orbit.end: must come after \"start\""},
        {R"({"duration": 1, "lenses": [{"lens": 2, "keyframes": [{"time": 0, "region": {"size": [1, 1]}}]}]})",
         "anim.json: lenses[0].keyframes[0].region.size: a polygon lens is shaped by its \"points\""},
        {R"({"duration": 1, "lenses": [{"lens": 2, "keyframes": [{"time": 0, "region": {"points": [[0, 0]]}}]}]})",
         "anim.json: lenses[0].keyframes[0].region.points: expected 3 [x, y] points, as many as the lens has"},
        {R"({"duration": 1, "lenses": [{"lens": 0, "keyframes": [{"time": 0, "easing": "bounce"}]}]})",
         "anim.json: lenses[0].keyframes[0].easing: unknown easing 'bounce' (known: linear, smooth)"},
        {R"({"duration": 1, "camera": {"keyframes": [{"time": 0, "eye": [1, 2]}]}})",
         "anim.json: camera.keyframes[0].eye: expected an array of 3 numbers"},
        {R"({"duration": 1, "fps": 30})", "anim.json: unknown key 'fps' (known: version, duration, frameRate, camera, lenses)"},
        {R"({"frameRate": 30})", "anim.json: missing \"duration\" (seconds)"},
        {R"({"duration": 0})", "anim.json: duration: must be more than 0 seconds"},
        {R"({"duration": 1, "version": 2})", "anim.json: version: this build reads version 1, got 2"},
        {R"({"duration": 1,)", "anim.json: invalid JSON: "},
    };
    for (const auto &c : cases) {
        const std::string message = errorIn(c.text);
        EXPECT_EQ(message.rfind(c.message, 0), 0u) << "got:      " << message << "\nexpected: " << c.message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(AnimationFile, AnAmbiguousLabelMustBeNamedByIndex) {
    const LensStack twins = parseLensStackJson(
        R"({"lenses": [{"type": "achromatic", "label": "same"}, {"type": "achromatic", "label": "same"}]})",
        "stack.json", registry()).lenses;
    const std::string message = errorOf([&] {
        parseAnimationJson(R"({"duration": 1, "lenses": [{"lens": "same"}]})", "anim.json", twins);
    });
    EXPECT_NE(message.find("lenses 0 and 1 are both labelled 'same': name one by its index"), std::string::npos)
        << message;
    // And the writer names such lenses by index.
    Animation animation;
    LensKeyframe keyframe;
    keyframe.enabled = false;
    animation.addLensKeyframe(1, keyframe);
    EXPECT_NE(animationJson(animation, twins).find("\"lens\": 1"), std::string::npos);
}

TEST(AnimationFile, MissingAndFolderFilesAreClearErrors) {
    const LensStack lenses = threeLenses();
    EXPECT_NE(errorOf([&] { readAnimationFile("/nonexistent/anim.json", lenses); })
                  .find("/nonexistent/anim.json: cannot open the animation file"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { readAnimationFile(fs::temp_directory_path(), lenses); }).find("is a folder"),
              std::string::npos);
}

TEST(AnimationFile, SweepSpecsNameALensByLabelOrIndex) {
    const LensStack lenses = threeLenses();
    Animation animation;
    animation.setDuration(5.0 / 30.0);
    addSweepSpec(animation, "reveal.distance=0:4", lenses);
    addSweepSpec(animation, "2.tint=1,0,0:0,0,1", lenses);
    ASSERT_EQ(animation.lensTracks().size(), 2u);
    EXPECT_EQ(animation.lensTracks()[0].lens, 0);
    EXPECT_EQ(animation.lensTracks()[0].keyframes.back().property("distance")->toReal(), 4.0);
    EXPECT_EQ(animation.lensTracks()[0].keyframes.back().time, animation.frameTime(4));
    EXPECT_EQ(animation.lensTracks()[1].keyframes.front().property("tint")->toColor(), glm::vec3(1, 0, 0));

    const struct {
        const char *spec;
        const char *message;
    } cases[] = {
        {"reveal.distance=0", "--sweep: 'reveal.distance=0': expected LENS.PROPERTY=FROM:TO"},
        {"revealdistance=0:1", "--sweep: 'revealdistance=0:1': expected LENS.PROPERTY=FROM:TO"},
        {"skin.distance=0:1", "--sweep: 'skin.distance=0:1': no lens of the session is labelled 'skin'"},
        {"7.distance=0:1", "--sweep: '7.distance=0:1': lens 7 is out of range"},
        {"grey.amont=0:1", "--sweep: 'grey.amont=0:1': unknown property 'amont' of lens 'achromatic'"},
        {"grey.amount=0:3", "--sweep: 'grey.amount=0:3': property 'amount': 3 is outside [0, 1]"},
    };
    for (const auto &c : cases) {
        const std::string message = errorOf([&] { addSweepSpec(animation, c.spec, lenses); });
        EXPECT_EQ(message.rfind(c.message, 0), 0u) << "got:      " << message << "\nexpected: " << c.message;
    }
}
