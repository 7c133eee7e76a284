// mvcl-render --animate, --turntable, --sweep and --frames as a user runs them: frames that equal
// single renders of the same values, a turntable that loops, a video, and bad input.

#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <mvcl/io/AnimationFile.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/Lens.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/view/ImageIO.h>

#include "lens/InTreeLensRegistry.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace mvcl;
using namespace mvcl::test;

namespace {

const char *const kSmall = " --size 96x72 --spp 1";

fs::path defaultLenses() {
    return fs::path(MVCL_TEST_DATA_DIR) / ".." / ".." / "assets" / "lenses" / "cube-in-cube.json";
}

fs::path scratch(const std::string &name) {
    const fs::path dir = outDir() / "animation" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

const LensRegistry &registry() {
    EXPECT_TRUE(test::inTreeLenses().loadErrors.empty()) << test::inTreeLenses().loadErrors.front().what();
    return test::inTreeLenses().registry;
}

/// Same size and every pixel equal (8-bit files: the same bytes decoded).
bool samePixels(const Framebuffer &a, const Framebuffer &b) {
    return a.width() == b.width() && a.height() == b.height() && a.pixels() == b.pixels();
}

void writeText(const fs::path &path, const std::string &text) { std::ofstream(path, std::ios::binary) << text; }

} // namespace

TEST(RenderAnimationCli, SweepFramesMatchSingleRendersOfTheSameValuesBitForBit) {
    const fs::path dir = scratch("sweep");
    const std::string sweeps = " --sweep reveal.distance=0:11 --sweep grey.amount=1:0.2 --frame-count 5";
    const CommandResult r = runRender("--lenses " + quoted(defaultLenses().string()) + kSmall + sweeps + " -o " +
                                      quoted((dir / "%04d.png").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // The camera never moves: the first frame traces every pixel, the others only what changed.
    EXPECT_NE(r.output.find("1 full, 4 re-traced only what their lenses changed"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "0005.png"));

    // Each frame's values, as the animation gives them, written into a lens-stack file of
    // their own and rendered once.
    LensStackDescription session = readLensStackFile(defaultLenses(), registry());
    Animation animation;
    animation.setDuration(5.0 / 30.0);
    addSweepSpec(animation, "reveal.distance=0:11", session.lenses);
    addSweepSpec(animation, "grey.amount=1:0.2", session.lenses);
    std::vector<double> distances;
    for (int frame = 0; frame < 5; ++frame) {
        for (const LensTrack &track : animation.lensTracks()) {
            Lens &lens = *session.lenses.lens(track.lens);
            for (const auto &[name, value] : Animation::propertiesAt(track, animation.frameTime(frame), lens.properties()))
                lens.setProperty(name, value);
            lens.commit();
        }
        distances.push_back(session.lenses.lens(0)->committedValues()[1].toReal());
        const fs::path stack = dir / ("single" + std::to_string(frame) + ".json");
        writeLensStackFile(stack, session);
        const fs::path single = dir / ("single" + std::to_string(frame) + ".png");
        const CommandResult one = runRender("--lenses " + quoted(stack.string()) + kSmall + " -o " + quoted(single.string()));
        ASSERT_EQ(one.exitCode, 0) << one.output;
        char name[16];
        std::snprintf(name, sizeof name, "%04d.png", frame);
        EXPECT_TRUE(samePixels(readImage(dir / name), readImage(single))) << "frame " << frame;
    }
    EXPECT_EQ(distances.front(), 0.0);
    EXPECT_EQ(distances.back(), 11.0);
    // The sweep changes the picture: frames that all looked alike would prove nothing.
    EXPECT_GT(compareImages(readImage(dir / "0000.png"), readImage(dir / "0004.png"), 8).differingFraction, 0.01);
}

TEST(RenderAnimationCli, AFrameRangeRendersTheSameFramesAsTheWholeAnimation) {
    const fs::path whole = scratch("range-whole"), part = scratch("range-part");
    const std::string animation = " --sweep reveal.distance=2:9 --frame-count 5";
    const std::string lenses = "--lenses " + quoted(defaultLenses().string()) + kSmall + animation;
    ASSERT_EQ(runRender(lenses + " -o " + quoted((whole / "%02d.png").string())).exitCode, 0);
    const CommandResult r = runRender(lenses + " --frames 2-3 -o " + quoted((part / "%02d.png").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FALSE(fs::exists(part / "01.png"));
    EXPECT_FALSE(fs::exists(part / "04.png"));
    for (const char *frame : {"02.png", "03.png"})
        EXPECT_TRUE(samePixels(readImage(whole / frame), readImage(part / frame))) << frame;
}

TEST(RenderAnimationCli, ATurntablesLastFrameIsOneStepBeforeItsFirst) {
    const fs::path dir = scratch("turntable");
    const CommandResult r =
        runRender("builtin:cube-in-cube" + std::string(kSmall) + " --turntable 4 -o " + quoted((dir / "%d.png").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("4 full, 0 re-traced"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "4.png")) << "the first frame again at the end";

    // Frame 0 is the scene's own view, exactly.
    ASSERT_EQ(runRender("builtin:cube-in-cube" + std::string(kSmall) + " -o " + quoted((dir / "still.png").string()))
                  .exitCode,
              0);
    EXPECT_TRUE(samePixels(readImage(dir / "0.png"), readImage(dir / "still.png")));
    // Frame 3 is the view turned one step (90 degrees) back about its up axis through its target.
    const Scene scene = loadScene("builtin:cube-in-cube");
    const CameraDesc &view = scene.cameras.front();
    const glm::dvec3 axis = glm::normalize(glm::dvec3(view.up)), v = glm::dvec3(view.eye - view.target);
    const glm::dvec3 back = glm::cross(v, axis) + axis * glm::dot(axis, v); // −90 degrees: cos 0, sin −1
    const glm::dvec3 eye = glm::dvec3(view.target) + back + glm::dvec3(scene.worldOrigin);
    const glm::dvec3 target = glm::dvec3(view.target) + glm::dvec3(scene.worldOrigin);
    char camera[256];
    std::snprintf(camera, sizeof camera, " --eye %.9g,%.9g,%.9g --target %.9g,%.9g,%.9g --up %.9g,%.9g,%.9g --fov %.9g",
                  eye.x, eye.y, eye.z, target.x, target.y, target.z, double(view.up.x), double(view.up.y),
                  double(view.up.z), double(view.verticalFovDegrees));
    ASSERT_EQ(runRender("builtin:cube-in-cube" + std::string(kSmall) + camera + " -o " +
                        quoted((dir / "step-back.png").string()))
                  .exitCode,
              0);
    const ImageDifference lastVsStepBack = compareImages(readImage(dir / "3.png"), readImage(dir / "step-back.png"), 8);
    EXPECT_LT(lastVsStepBack.differingFraction, 0.01);
    EXPECT_GT(compareImages(readImage(dir / "3.png"), readImage(dir / "0.png"), 8).differingFraction, 0.1);
}

TEST(RenderAnimationCli, AnAnimationFileMovesTheCameraAndTheLenses) {
    const fs::path dir = scratch("file");
    writeText(dir / "anim.json", R"({"duration": 1, "frameRate": 3,
        "camera": {"keyframes": [{"time": 0, "fov": 40}, {"time": 1, "fov": 25, "easing": "smooth"}]},
        "lenses": [{"lens": "reveal", "keyframes": [{"time": 0, "region": {"center": [0.3, 0.5]}},
                                                    {"time": 0.6, "region": {"center": [0.7, 0.5]}}]}]})");
    const CommandResult r = runRender("--lenses " + quoted(defaultLenses().string()) + kSmall + " --animate " +
                                      quoted((dir / "anim.json").string()) + " -o " + quoted((dir / "f%02d.png").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("animation  3 frames at 3 fps"), std::string::npos) << r.output;
    for (const char *frame : {"f00.png", "f01.png", "f02.png"}) EXPECT_TRUE(fs::exists(dir / frame)) << frame;
    EXPECT_GT(compareImages(readImage(dir / "f00.png"), readImage(dir / "f02.png"), 8).differingFraction, 0.1);
}

// The shortcuts write the file for you: --save-animation keeps what --turntable and --sweep made,
// and rendering that file gives the same frames.
TEST(RenderAnimationCli, ShortcutsSaveTheirAnimationAsAFileThatRendersTheSameFrames) {
    const fs::path dir = scratch("save");
    const std::string lenses = "--lenses " + quoted(defaultLenses().string()) + kSmall;
    const CommandResult r = runRender(lenses + " --turntable 4 --sweep reveal.distance=0:6 --save-animation " +
                                      quoted((dir / "turn.json").string()) + " -o " + quoted((dir / "a%d.png").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("saved      " + (dir / "turn.json").string()), std::string::npos) << r.output;
    const LensStackDescription stack = readLensStackFile(defaultLenses(), registry());
    const Animation saved = readAnimationFile(dir / "turn.json", stack.lenses);
    EXPECT_EQ(saved.frameCount(), 4);
    const CommandResult again = runRender(lenses + " --animate " + quoted((dir / "turn.json").string()) + " -o " +
                                          quoted((dir / "b%d.png").string()));
    ASSERT_EQ(again.exitCode, 0) << again.output;
    for (int i = 0; i < 4; ++i) {
        const std::string name = std::to_string(i) + ".png";
        EXPECT_TRUE(samePixels(readImage(dir / ("a" + name)), readImage(dir / ("b" + name)))) << name;
    }
    const CommandResult alone = runRender(lenses + " --save-animation " + quoted((dir / "none.json").string()));
    EXPECT_EQ(alone.exitCode, 2) << alone.output;
}

#ifdef MVCL_TEST_FFMPEG_MODULE
TEST(RenderAnimationCli, WritesAVideo) {
    const fs::path dir = scratch("video");
    const CommandResult r = runRender("--lenses " + quoted(defaultLenses().string()) + kSmall +
                                      " --sweep reveal.distance=0:9 --frame-count 6 --frame-rate 12 -o " +
                                      quoted((dir / "clip.mp4").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("wrote      " + (dir / "clip.mp4").string()), std::string::npos) << r.output;
    EXPECT_GT(fs::file_size(dir / "clip.mp4"), 500u);
}
#endif

TEST(RenderAnimationCli, BadInputIsOneLineNamingTheFileAndTheProblem) {
    const fs::path dir = scratch("bad");
    const std::string lenses = "--lenses " + quoted(defaultLenses().string()) + kSmall;
    const auto animationFile = [&](const std::string &name, const std::string &text) {
        writeText(dir / name, text);
        return " --animate " + quoted((dir / name).string());
    };
    const struct {
        std::string args;
        int exitCode;
        std::string message;
    } cases[] = {
        {lenses + animationFile("property.json", R"({"duration": 1, "lenses": [{"lens": 0, "keyframes": [
             {"time": 0, "properties": {"depth": 1}}]}]})"),
         1, (dir / "property.json").string() + ": lenses[0].keyframes[0].properties: unknown property 'depth' of lens 'layer'"},
        {lenses + animationFile("range.json", R"({"duration": 1, "lenses": [{"lens": "grey", "keyframes": [
             {"time": 0, "properties": {"amount": 1.5}}]}]})"),
         1, (dir / "range.json").string() + ": lenses[0].keyframes[0].properties.amount: "},
        {lenses + animationFile("time.json", R"({"duration": 1, "camera": {"keyframes": [{"time": 2, "fov": 30}]}})"),
         1, (dir / "time.json").string() + ": camera.keyframes[0].time: time 2 is outside the duration (0 to 1.0 s)"},
        {lenses + " --animate " + quoted((dir / "missing.json").string()), 1,
         (dir / "missing.json").string() + ": cannot open the animation file"},
        {lenses + " --sweep reveal.dist=0:1", 2, "command line: --sweep: 'reveal.dist=0:1': unknown property 'dist'"},
        {lenses + " --sweep reveal.distance=0:1 --frame-count 5 --frames 3-5", 2,
         "command line: --frames 3-5: the animation has 5 frames (0 to 4)"},
        {lenses + " --frames 0-1", 2, "command line: --frames needs --animate, --turntable or --sweep"},
        {lenses + " --turntable 3 --frame-count 4", 2, "command line: --turntable N sets the frame count already"},
        {lenses + " --turntable 3 --convergence-log " + quoted((dir / "log.csv").string()), 2,
         "command line: --convergence-log logs the passes of one image, not of an animation's frames"},
        {lenses + " --turntable 3 -o " + quoted((dir / "still.png").string()), 3,
         (dir / "still.png").string() + ": numbered frames need one frame number in the name"},
    };
    for (const auto &c : cases) {
        const CommandResult r = runRender(c.args);
        EXPECT_EQ(r.exitCode, c.exitCode) << c.args << "\n" << r.output;
        EXPECT_EQ(r.output.rfind("mvcl-render: " + c.message, 0), 0u) << c.args << "\ngot: " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    }
    // An output folder that cannot be made (a file is in the way): exit 3 before rendering.
    writeText(dir / "blocker", "a file");
    const std::string target = (dir / "blocker" / "%04d.png").string();
    const CommandResult r = runRender(lenses + " --turntable 3 -o " + quoted(target));
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_EQ(r.output.rfind("mvcl-render: " + target + ": cannot create the folder", 0), 0u) << r.output;
}

TEST(RenderAnimationCli, AnInterruptedRenderLeavesTheFramesItWroteWhole) {
    const fs::path dir = scratch("interrupted");
    // Far more frames than run before the signal; stop once two frames are on disk.
    const std::string command = std::string(MVCL_RENDER_EXE) + " --no-progress builtin:cube-in-cube --size 64x48 --spp 1" +
                                " --turntable 100000 -o " + quoted((dir / "%06d.png").string());
    const std::string script = command + " > /dev/null & pid=$!; i=0; while [ ! -e " +
                               quoted((dir / "000001.png").string()) +
                               " ] && [ $i -lt 600 ]; do sleep 0.05; i=$((i+1)); done; kill -INT $pid; wait $pid; "
                               "echo exit=$?";
    const CommandResult r = runCommand("sh -c '" + script + "'"); // the script quotes its paths with "
    EXPECT_NE(r.output.find("exit=130"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("mvcl-render: interrupted after"), std::string::npos) << r.output;
    int frames = 0;
    for (const auto &entry : fs::directory_iterator(dir)) {
        EXPECT_EQ(entry.path().extension(), ".png") << "left behind: " << entry.path();
        const Framebuffer image = readImage(entry.path()); // throws on a torn file
        EXPECT_EQ(image.width(), 64);
        ++frames;
    }
    EXPECT_GE(frames, 2);
}
