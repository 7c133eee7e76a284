// RecoveryWriter: at most one write per interval on an injected clock, the trailing write that
// lands the last change, flush and discard, a failed write retried one interval later.

#include <mvcl/controller/RecoveryWriter.h>
#include <mvcl/io/SessionFile.h>
#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace mvcl::test {
namespace {

class RecoveryWriterTest : public ::testing::Test {
protected:
    void SetUp() override {
        folder = fs::temp_directory_path() / "mvcl-recovery-writer-test" /
                 ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(folder);
        fs::create_directories(folder);
        writer.setPath(folder / "work.recovery.json");
    }

    /// The session at "edit N", told apart by its scene name (only written, never loaded).
    RecoveryWriter::Describe describe(int edit) {
        return [this, edit] {
            ++describeCalls;
            LensStackDescription description;
            description.scene = "builtin:edit-" + std::to_string(edit);
            return SessionDescription::fromView(description);
        };
    }

    std::string written() const {
        std::ifstream in(writer.path());
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }
    bool holds(int edit) const { return written().find("\"builtin:edit-" + std::to_string(edit) + "\"") != std::string::npos; }

    fs::path folder;
    RecoveryWriter::Clock::time_point now{std::chrono::hours(1)};
    RecoveryWriter writer{[this] { return now; }};
    int describeCalls = 0;
};

TEST_F(RecoveryWriterTest, WritesTheFirstChangeAtOnceThenAtMostOncePerInterval) {
    EXPECT_EQ(writer.interval(), 2000ms) << "the default interval";
    writer.sessionChanged(describe(1));
    EXPECT_EQ(writer.writeCount(), 1);
    EXPECT_TRUE(holds(1));
    EXPECT_FALSE(writer.isPending());

    // A drag: 60 changes a second for 5 seconds.
    int edit = 1;
    for (int frame = 1; frame <= 300; ++frame) {
        now += 1000ms / 60;
        writer.sessionChanged(describe(++edit));
    }
    // Writes at 2 s and 4 s after the first (frames 120 and 240, give or take the rounding of
    // 1000/60 ms), never more.
    EXPECT_EQ(writer.writeCount(), 3);
    EXPECT_EQ(describeCalls, 3) << "the session is described only when a write is due";
    EXPECT_TRUE(writer.isPending()) << "the changes after the last write";
    EXPECT_FALSE(holds(edit));
}

TEST_F(RecoveryWriterTest, TheTrailingWriteLandsTheLastChangeOnceTheIntervalHasPassed) {
    writer.sessionChanged(describe(1));
    now += 500ms;
    writer.sessionChanged(describe(2));
    EXPECT_TRUE(holds(1));
    writer.update(describe(2));
    EXPECT_EQ(writer.writeCount(), 1) << "0.5 s after the last write: not yet";
    now += 1499ms;
    writer.update(describe(2));
    EXPECT_EQ(writer.writeCount(), 1);
    now += 1ms;
    writer.update(describe(2));
    EXPECT_EQ(writer.writeCount(), 2);
    EXPECT_TRUE(holds(2));
    EXPECT_FALSE(writer.isPending());
    now += 10s;
    writer.update(describe(3));
    EXPECT_EQ(writer.writeCount(), 2) << "nothing pending: nothing written";
}

TEST_F(RecoveryWriterTest, FlushWritesAPendingChangeNowAndOnlyThen) {
    writer.flush(describe(0));
    EXPECT_EQ(writer.writeCount(), 0);
    EXPECT_FALSE(fs::exists(writer.path()));
    writer.sessionChanged(describe(1));
    now += 100ms;
    writer.sessionChanged(describe(2));
    writer.flush(describe(2));
    EXPECT_EQ(writer.writeCount(), 2);
    EXPECT_TRUE(holds(2));
}

TEST_F(RecoveryWriterTest, DiscardRemovesTheCopyAndForgetsThePendingChange) {
    writer.sessionChanged(describe(1));
    now += 100ms;
    writer.sessionChanged(describe(2));
    writer.discard();
    EXPECT_FALSE(fs::exists(writer.path()));
    EXPECT_FALSE(writer.isPending());
    now += 10s;
    writer.update(describe(2));
    EXPECT_FALSE(fs::exists(writer.path()));
    writer.discard(); // nothing there: no error
}

TEST_F(RecoveryWriterTest, ZeroIntervalWritesEveryChange) {
    writer.setInterval(0ms);
    for (int edit = 1; edit <= 5; ++edit) writer.sessionChanged(describe(edit));
    EXPECT_EQ(writer.writeCount(), 5);
    EXPECT_TRUE(holds(5));
}

TEST_F(RecoveryWriterTest, WithoutAPathChangesWaitForOne) {
    writer.setPath({});
    writer.sessionChanged(describe(1));
    EXPECT_TRUE(writer.isPending());
    writer.setPath(folder / "later.json");
    writer.update(describe(1));
    EXPECT_TRUE(holds(1));
}

TEST_F(RecoveryWriterTest, AFailedWriteThrowsNamingTheFileAndIsRetriedOneIntervalLater) {
    const fs::path blocked = folder / "blocker" / "copy.json";
    std::ofstream(folder / "blocker") << "a file where the folder should be";
    writer.setPath(blocked);
    try {
        writer.sessionChanged(describe(1));
        FAIL() << "a write under a file cannot succeed";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find(blocked.parent_path().string()), std::string::npos) << e.what();
    }
    EXPECT_TRUE(writer.isPending());
    now += 100ms;
    EXPECT_NO_THROW(writer.sessionChanged(describe(2))) << "not due: not tried";
    fs::remove(folder / "blocker");
    now += 1900ms;
    writer.update(describe(2));
    EXPECT_TRUE(holds(2));
    EXPECT_FALSE(writer.isPending());
}

TEST_F(RecoveryWriterTest, NoTemporaryFilesAreLeftBeside) {
    writer.setInterval(0ms);
    for (int edit = 1; edit <= 20; ++edit) writer.sessionChanged(describe(edit));
    int files = 0;
    for ([[maybe_unused]] const auto &entry : fs::directory_iterator(folder)) ++files;
    EXPECT_EQ(files, 1);
}

} // namespace
} // namespace mvcl::test
