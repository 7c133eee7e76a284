// mvcl-viewer in a real window (Xvfb + Mesa llvmpipe, OpenGL 3.3 core), driven by --script:
// three overlapping lenses added and dragged over a real layered model, the session saved with
// a screenshot; then a second viewer opens that session and must show the same image, which
// must also match the committed baseline. Regenerate the baseline with MVCL_UPDATE_GOLDEN=1.

#include "ImageCompare.h"
#include "apps/RenderCliRunner.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

fs::path viewerDir() {
    const fs::path dir = outDir() / "viewer";
    fs::create_directories(dir);
    return dir;
}

void writeScript(const fs::path &file, const std::string &text) {
    std::ofstream(file) << text;
}

/// The viewer under a virtual X server, 1280×720 window (a 900×720 view beside the panels),
/// fixed sampling so that an image does not depend on when edits arrived.
/// `environment`: VAR=value words for the viewer's environment (e.g. MVCL_PLUGIN_PATH).
CommandResult runViewer(const std::string &args, const std::string &environment = "") {
    return runCommand(environment + " xvfb-run -a -s '-screen 0 1400x900x24' " + std::string(MVCL_VIEWER_EXE) +
                      " --size 1280x720 --sampling fixed --spp 4 " + args);
}

} // namespace

TEST(ViewerEndToEnd, ThreeDraggedLensesSurviveASavedAndReopenedSession) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewerDir();
    const fs::path session = dir / "session.json", first = dir / "first.png", second = dir / "second.png";
    for (const fs::path &f : {session, first, second}) fs::remove(f);
    const std::string kidney = dataPath("models/HRA_Kidney_Female_Left/VH_F_Kidney_L.glb");

    writeScript(dir / "build.txt", R"(# three overlapping lenses, each dragged
wait-converged
add-lens layer 0.45 0.5
set-property 0 layers 1-
drag left 405 360 430 350 6
add-lens achromatic 0.6 0.45
drag left 540 324 520 310 6
add-lens shadow 0.4 0.6
drag left 360 432 380 420 6
expect-lenses 3
wait-converged
screenshot )" + first.string() + R"(
save-session )" + session.string() + R"(
quit
)");
    const CommandResult build = runViewer(quoted(kidney) + " --script " + quoted((dir / "build.txt").string()));
    ASSERT_EQ(build.exitCode, 0) << build.output;
    ASSERT_TRUE(fs::exists(first)) << build.output;
    ASSERT_TRUE(fs::exists(session)) << build.output;

    writeScript(dir / "reopen.txt", "wait-converged\nexpect-lenses 3\nscreenshot " + second.string() + "\nquit\n");
    const CommandResult reopen = runViewer("--session " + quoted(session.string()) + " --script " +
                                           quoted((dir / "reopen.txt").string()));
    ASSERT_EQ(reopen.exitCode, 0) << reopen.output;
    ASSERT_TRUE(fs::exists(second)) << reopen.output;

    const mvcl::Framebuffer a = mvcl::readImage(first), b = mvcl::readImage(second);
    const ImageDifference same = compareImages(a, b, 2);
    EXPECT_LT(same.differingFraction, 0.001) << "max channel delta " << same.maxChannelDelta;

    MVCL_EXPECT_MATCHES_GOLDEN(first, fs::path(MVCL_GOLDEN_DIR) / "viewer-three-lenses.png");
}

TEST(ViewerEndToEnd, ABrokenScriptOrSessionIsAClearErrorNotACrash) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewerDir();
    writeScript(dir / "typo.txt", "wait-converged\nmvoe 10 10\n");
    // Checked with the command line, before any window system is touched: no display needed.
    const CommandResult typo = runCommand("env -u DISPLAY " + std::string(MVCL_VIEWER_EXE) + " builtin:onion --script " +
                                          quoted((dir / "typo.txt").string()));
    EXPECT_EQ(typo.exitCode, 2) << typo.output;
    EXPECT_NE(typo.output.find("typo.txt:2"), std::string::npos) << typo.output;

    std::ofstream(dir / "broken.json") << "{ \"version\": 1, \"lenses\": [ {\"type\": \"nope\"} ] }";
    writeScript(dir / "quit.txt", "wait-converged\nexpect-lenses 0\nquit\n");
    const CommandResult broken = runViewer("builtin:onion --session " + quoted((dir / "broken.json").string()) +
                                           " --script " + quoted((dir / "quit.txt").string()));
    EXPECT_EQ(broken.exitCode, 0) << "the viewer keeps running on its default view\n" << broken.output;
    EXPECT_NE(broken.output.find("broken.json"), std::string::npos) << broken.output;
}

// Keyframes added from the view go to an animation file; playing it back while recording the
// view writes frames at the recording's fixed rate, the size of the view without the panels.
TEST(ViewerEndToEnd, KeyframesAddedFromTheViewPlayBackWhileTheViewIsRecorded) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewerDir() / "animation";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path animation = dir / "anim.json", frames = dir / "rec";
    writeScript(dir / "animate.txt", "wait-converged\nadd-lens layer 0.5 0.5\nselect 0\nadd-keyframe " +
                                         animation.string() + " 0\nkey 3\nset-property 0 distance 0.05\n"
                                         "add-keyframe " + animation.string() + " 1\nrecord " +
                                         (frames / "%04d.png").string() + " 10\nplay " + animation.string() +
                                         "\nstop-recording\nexpect-lenses 1\nquit\n");
    const CommandResult run = runViewer(quoted(dataPath("models/HRA_Kidney_Female_Left/VH_F_Kidney_L.glb")) +
                                        " --script " + quoted((dir / "animate.txt").string()));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    std::ifstream file(animation);
    const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"time\": 1.0"), std::string::npos) << text;
    EXPECT_NE(text.find("\"distance\": \"0.05\""), std::string::npos) << text;
    int recorded = 0;
    for (const auto &entry : fs::directory_iterator(frames)) {
        const mvcl::Framebuffer image = mvcl::readImage(entry.path());
        EXPECT_EQ(image.width(), 900) << entry.path();
        EXPECT_EQ(image.height(), 720) << entry.path();
        ++recorded;
    }
    // The animation plays for one second at least, recorded at 10 frames per second.
    EXPECT_GE(recorded, 10);
    EXPECT_TRUE(fs::exists(frames / "0000.png"));
}

// The command line's turntable and sweep, written from the viewer's Animation panel (its script
// command), play back while the view is recorded.
TEST(ViewerEndToEnd, ATurntableWrittenInTheViewerPlaysWhileTheViewIsRecorded) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewerDir() / "turntable";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path animation = dir / "turn.json", frames = dir / "rec";
    writeScript(dir / "turn.txt", "wait-converged\nadd-lens layer 0.5 0.5\nwrite-turntable " + animation.string() +
                                      " 15 0.distance=0:0.1\nrecord " + (frames / "%04d.png").string() +
                                      " 10\nplay " + animation.string() + "\nstop-recording\nquit\n");
    const CommandResult run = runViewer("builtin:cube-in-cube --script " + quoted((dir / "turn.txt").string()));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("15 frames; Play or Record it"), std::string::npos) << run.output;
    std::ifstream file(animation);
    const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"orbit\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"distance\""), std::string::npos) << text;
    int recorded = 0;
    for (const auto &entry : fs::directory_iterator(frames)) recorded += entry.path().extension() == ".png";
    // Half a second of turntable (15 frames at 30 fps), recorded at 10 frames per second.
    EXPECT_GE(recorded, 4);
}

TEST(ViewerEndToEnd, AFaultyPluginsLensIsDisabledReportedAndKeptInTheSession) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewerDir();
    const fs::path session = dir / "faulty-session.json";
    fs::remove(session);
    // fixture-faulty-nan: its contribution has a NaN colour map (tests/lens/fixtures/FixtureFaulty.cpp).
    const std::string environment = "MVCL_PLUGIN_PATH=" + quoted(MVCL_FAULTY_PLUGIN_DIR);
    const std::string reported = "disabled: lens 'fixture-faulty-nan': contribution: the colour map is not finite";
    writeScript(dir / "faulty.txt", R"(wait-converged
add-lens fixture-faulty-nan 0.5 0.5
add-lens achromatic 0.4 0.4
drag left 360 288 380 300 4
expect-lenses 2
wait-converged
save-session )" + session.string() + R"(
quit
)");
    const CommandResult build =
        runViewer("builtin:cube-in-cube --script " + quoted((dir / "faulty.txt").string()), environment);
    ASSERT_EQ(build.exitCode, 0) << build.output;
    EXPECT_NE(build.output.find("mvcl-viewer: lens 0 "), std::string::npos) << build.output;
    EXPECT_NE(build.output.find(reported), std::string::npos) << build.output;
    std::ifstream in(session);
    const std::string saved((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(saved.find("\"type\": \"fixture-faulty-nan\""), std::string::npos) << saved;
    EXPECT_NE(saved.find("\"enabled\": false"), std::string::npos) << saved;

    // Reopened, the lens is there again, disabled, and the user is told again why.
    writeScript(dir / "faulty-reopen.txt", "wait-converged\nexpect-lenses 2\nquit\n");
    const CommandResult reopen = runViewer("--session " + quoted(session.string()) + " --script " +
                                           quoted((dir / "faulty-reopen.txt").string()), environment);
    ASSERT_EQ(reopen.exitCode, 0) << reopen.output;
    EXPECT_NE(reopen.output.find(reported), std::string::npos) << reopen.output;
}

TEST(ViewerEndToEnd, AtStartARecoveryCopyNewerThanItsSessionIsOffered) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewerDir() / "recovery";
    fs::create_directories(dir);
    const fs::path session = dir / "work.json", recovery = dir / "work.recovery.json";
    std::ofstream(session) << R"({"scene": "builtin:cube-in-cube", "lenses": []})";
    std::ofstream(recovery) << R"({"scene": "builtin:cube-in-cube", "lenses": [{"type": "achromatic"}]})";
    writeScript(dir / "quit.txt", "wait-converged\nquit\n");
    const std::string args = "--session " + quoted(session.string()) + " --script " + quoted((dir / "quit.txt").string());
    const std::string offer = "the last session was not saved; its recovery copy is " + recovery.string();

    fs::last_write_time(recovery, fs::last_write_time(session) + std::chrono::seconds(10));
    const CommandResult newer = runViewer(args);
    ASSERT_EQ(newer.exitCode, 0) << newer.output;
    EXPECT_NE(newer.output.find(offer), std::string::npos) << newer.output;

    fs::last_write_time(recovery, fs::last_write_time(session) - std::chrono::seconds(10));
    const CommandResult older = runViewer(args);
    ASSERT_EQ(older.exitCode, 0) << older.output;
    EXPECT_EQ(older.output.find("recovery copy is"), std::string::npos) << "saved since: nothing to offer\n" << older.output;
}

TEST(ViewerEndToEnd, AClipBoxFaceAndRingDraggedInTheViewCutAsTheGoldenImage) {
    // The 3D handles through the window: a face dragged outward and a ring turned, by pointer
    // drags at the places the controller draws them (gizmo-drag), then the cut image against
    // the baseline, and the oriented box kept by the session.
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = viewerDir();
    const fs::path shot = dir / "gizmo.png", session = dir / "gizmo.json", reopened = dir / "gizmo-reopened.png";
    for (const fs::path &f : {shot, session, reopened}) fs::remove(f);
    writeScript(dir / "gizmo.txt", R"(wait-converged
add-lens clip 0.5 0.5
set-property 0 box 0.3,0.3,0.3,0.7,0.7,0.7
gizmo-drag 0 +x 60 -10
gizmo-drag 0 rotate-y 40 25
gizmo-drag 0 +y 0 -30
wait-converged
screenshot )" + shot.string() + R"(
save-session )" + session.string() + R"(
quit
)");
    const CommandResult run = runViewer("builtin:cube-in-cube --script " + quoted((dir / "gizmo.txt").string()));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    ASSERT_TRUE(fs::exists(shot)) << run.output;
    std::ifstream sessionFile(session);
    const std::string saved((std::istreambuf_iterator<char>(sessionFile)), std::istreambuf_iterator<char>());
    EXPECT_NE(saved.find("\"boxRotation\""), std::string::npos) << saved;
    EXPECT_EQ(saved.find("\"boxRotation\": \"1,0,0,0,0,1,0,0,0,0,1,0\""), std::string::npos)
        << "the ring turned the box: " << saved;

    writeScript(dir / "gizmo-reopen.txt", "wait-converged\nscreenshot " + reopened.string() + "\nquit\n");
    const CommandResult reopen =
        runViewer("--session " + quoted(session.string()) + " --script " + quoted((dir / "gizmo-reopen.txt").string()));
    ASSERT_EQ(reopen.exitCode, 0) << reopen.output;
    const mvcl::Framebuffer image = mvcl::readImage(shot);
    const ImageDifference same = compareImages(image, mvcl::readImage(reopened), 2);
    EXPECT_LT(same.differingFraction, 0.001) << "max channel delta " << same.maxChannelDelta;

    MVCL_EXPECT_MATCHES_GOLDEN(shot, fs::path(MVCL_GOLDEN_DIR) / "viewer-gizmo-clip.png");

    // A handle that is not drawn is a clear script error.
    writeScript(dir / "gizmo-bad.txt", "add-lens clip 0.5 0.5\ngizmo-drag 0 radius 5 5\nquit\n");
    const CommandResult bad = runViewer("builtin:cube-in-cube --script " + quoted((dir / "gizmo-bad.txt").string()));
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("no handle 'radius'"), std::string::npos) << bad.output;
}
