// The recovery copy under SIGKILL: mvcl-viewer (Xvfb) replays a long drag in three legs, saving
// the session after each, and is killed at several moments. Every time, the session file and the
// recovery copy must parse and hold a state of that drag (the lens on its path, the copy never
// behind the session); then the next start offers the copy, and "recovery restore" brings the
// lens back where the copy has it, "recovery discard" removes the copy.

#include "apps/RenderCliRunner.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace fs = std::filesystem;
using namespace mvcl::test;

namespace {

// A 900×720 view (1280×720 window beside the panels): the lens starts at x = 270 px (0.3) and is
// dragged to 360, 450 and 540 px (0.4, 0.5, 0.6) at y = 360 (0.5).
constexpr double kStartX = 0.3, kEndX = 0.6, kY = 0.5;

std::string viewerCommand(const std::string &args) {
    return std::string(MVCL_VIEWER_EXE) + " --size 1280x720 --sampling fixed --spp 1 " + args;
}

CommandResult runViewer(const std::string &args) {
    return runCommand("xvfb-run -a -s '-screen 0 1400x900x24' " + viewerCommand(args));
}

/// The lens centre of a session file; nothing when the file does not parse or holds no single lens.
std::optional<std::pair<double, double>> lensCenter(const fs::path &file, std::string &problem) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    try {
        const nlohmann::json json = nlohmann::json::parse(text.str());
        const nlohmann::json &lenses = json.at("lenses");
        if (lenses.size() != 1) {
            problem = std::to_string(lenses.size()) + " lenses";
            return std::nullopt;
        }
        const nlohmann::json &center = lenses[0].at("region").at("center");
        return std::make_pair(center.at(0).get<double>(), center.at(1).get<double>());
    } catch (const std::exception &e) {
        problem = e.what();
        return std::nullopt;
    }
}

bool onTheDrag(const std::pair<double, double> &c) {
    return std::abs(c.second - kY) < 1e-3 && c.first > kStartX - 1e-3 && c.first < kEndX + 1e-3;
}

} // namespace

TEST(ViewerEndToEnd, ARecoveryCopySurvivesSigkillMidDragAndIsRestoredAtTheNextStart) {
    ASSERT_EQ(runCommand("command -v xvfb-run").exitCode, 0) << "xvfb-run is missing (scripts/bootstrap.sh installs it)";
    const fs::path dir = outDir() / "viewer" / "recovery-kill";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path session = dir / "work.json", copy = dir / "work.recovery.json";

    std::ofstream(dir / "make.txt") << "add-lens achromatic " << kStartX << " " << kY << "\nsave-session "
                                    << session.string() << "\nquit\n";
    const CommandResult made = runViewer("builtin:cube-in-cube --script " + quoted((dir / "make.txt").string()));
    ASSERT_EQ(made.exitCode, 0) << made.output;
    std::string problem;
    ASSERT_TRUE(lensCenter(session, problem)) << problem;
    EXPECT_FALSE(fs::exists(copy)) << "saved, then a clean exit: nothing to recover";
    // Every run starts from this session: a run saves after each leg of its drag.
    const fs::path start = dir / "start.json";
    fs::copy_file(session, start, fs::copy_options::overwrite_existing);

    // Three legs of 150 frames each (about 2.5 s at 60 frames a second under Xvfb), saved after
    // each leg; then idle until killed.
    std::ofstream(dir / "drag.txt") << "drag left 270 360 360 360 150\nsave-session " << session.string()
                                    << "\ndrag left 360 360 450 360 150\nsave-session " << session.string()
                                    << "\ndrag left 450 360 540 360 150\nsave-session " << session.string()
                                    << "\nwait-frames 100000000\n";
    // The shell waits for the first write of the copy (the drag has begun), then kills the viewer
    // after `delay` seconds more.
    const std::string viewer = viewerCommand("--session " + quoted(session.string()) + " --script " +
                                             quoted((dir / "drag.txt").string()));
    int midDragCopies = 0;
    std::optional<std::pair<double, double>> lastCopy;
    // A kill between creating a temporary file and renaming it leaves the temporary behind: the
    // next viewer's first write of the same file removes it.
    const auto temporaries = [&dir] {
        std::vector<fs::path> found;
        for (const fs::directory_entry &entry : fs::directory_iterator(dir))
            if (entry.path().filename().string().find(".part-") != std::string::npos) found.push_back(entry.path());
        return found;
    };
    std::vector<fs::path> leftByTheLastKill;
    for (const double delay : {0.3, 1.7, 3.2, 5.9}) {
        fs::remove(copy);
        fs::copy_file(start, session, fs::copy_options::overwrite_existing);
        std::ofstream(dir / "kill.sh") << viewer << " &\npid=$!\nn=0\n"
                                       << "while [ ! -f " << quoted(copy.string()) << " ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n+1)); done\n"
                                       << "sleep " << delay << "\nkill -9 $pid\nwait $pid\necho \"viewer exit $?\"\n";
        const CommandResult run = runCommand("xvfb-run -a -s '-screen 0 1400x900x24' sh " + quoted((dir / "kill.sh").string()));
        ASSERT_NE(run.output.find("viewer exit 137"), std::string::npos) << "killed by SIGKILL after " << delay << " s\n" << run.output;

        for (const fs::path &left : leftByTheLastKill)
            EXPECT_FALSE(fs::exists(left)) << "left by the kill before and not removed by the next write: " << left;
        leftByTheLastKill = temporaries();
        const auto saved = lensCenter(session, problem);
        ASSERT_TRUE(saved) << "session file after a kill at " << delay << " s: " << problem;
        EXPECT_TRUE(onTheDrag(*saved)) << saved->first << ", " << saved->second;
        std::printf("killed %.1f s into the drag: session lens at x = %.4f", delay, saved->first);
        if (!fs::exists(copy)) {
            std::printf(", no recovery copy (saved, nothing written since)\n");
            continue;
        }
        const auto recovered = lensCenter(copy, problem);
        ASSERT_TRUE(recovered) << "recovery copy after a kill at " << delay << " s: " << problem;
        std::printf(", recovery copy at x = %.4f\n", recovered->first);
        EXPECT_TRUE(onTheDrag(*recovered)) << recovered->first << ", " << recovered->second;
        EXPECT_GE(recovered->first, saved->first - 1e-3) << "the copy is never older than the session";
        ++midDragCopies;
        lastCopy = recovered;
        fs::copy_file(copy, dir / "kept.json", fs::copy_options::overwrite_existing);
    }
    ASSERT_GT(midDragCopies, 0) << "no kill landed mid-drag: the copy is not written while dragging";
    std::printf("%d of 4 kills left a recovery copy\n", midDragCopies);

    // The next start offers the last copy; restoring it brings the lens back where it was.
    fs::copy_file(dir / "kept.json", copy, fs::copy_options::overwrite_existing);
    fs::last_write_time(copy, fs::last_write_time(session) + std::chrono::seconds(2));
    const fs::path restored = dir / "restored.json";
    std::ofstream(dir / "restore.txt") << "recovery restore\nexpect-lenses 1\nsave-session " << restored.string()
                                       << "\nquit\n";
    const CommandResult restore = runViewer("--session " + quoted(session.string()) + " --script " +
                                            quoted((dir / "restore.txt").string()));
    ASSERT_EQ(restore.exitCode, 0) << restore.output;
    EXPECT_NE(restore.output.find("the last session was not saved; its recovery copy is " + copy.string()),
              std::string::npos) << restore.output;
    const auto back = lensCenter(restored, problem);
    ASSERT_TRUE(back) << problem;
    EXPECT_NEAR(back->first, lastCopy->first, 1e-4);
    EXPECT_NEAR(back->second, lastCopy->second, 1e-4);
    EXPECT_FALSE(fs::exists(copy)) << "saved (under another name): nothing left to recover";

    // Declined: the copy is removed, and nothing is offered at the start after.
    fs::copy_file(restored, copy);
    fs::last_write_time(copy, fs::last_write_time(session) + std::chrono::seconds(2));
    std::ofstream(dir / "discard.txt") << "recovery discard\nexpect-lenses 1\nquit\n";
    const CommandResult discard = runViewer("--session " + quoted(session.string()) + " --script " +
                                            quoted((dir / "discard.txt").string()));
    ASSERT_EQ(discard.exitCode, 0) << discard.output;
    EXPECT_FALSE(fs::exists(copy));
    std::ofstream(dir / "again.txt") << "recovery restore\nquit\n";
    const CommandResult again = runViewer("--session " + quoted(session.string()) + " --script " +
                                          quoted((dir / "again.txt").string()));
    EXPECT_EQ(again.exitCode, 1) << "nothing offered: the script's answer fails\n" << again.output;
    EXPECT_NE(again.output.find("no recovery copy was offered"), std::string::npos) << again.output;
}
