#pragma once
/// \file RecoveryWriter.h
/// The recovery copy of a session, written often enough that a crash loses at most a few
/// seconds of work and seldom enough that a long drag does not write a file every frame.
///
/// Whoever owns the session (the Controller, or a document of several views) calls
/// sessionChanged() after every change, drag moves included, and update() once per frame:
///
/// - a change writes at once when the last write is at least interval() old (2 s by default),
///   else it is remembered as pending;
/// - update() writes a pending change once interval() has passed since the last write (the
///   trailing write), so the last state always lands, even when the changes stop;
/// - flush() writes a pending change now (a clean exit with unsaved changes);
/// - discard() forgets a pending change and removes the file (the session was saved, or the
///   user chose not to restore the copy).
///
/// Every write goes through writeSessionFile (a session of one plain view is written as a
/// lens-stack file, as always): a temporary file beside the copy, fsync, then
/// rename over it. A process killed at any moment leaves the previous copy or the new one,
/// never a part of one. The description is asked for only when a write is due, so a change
/// costs nothing until then. Everything runs on the caller's thread.

#include <mvcl/core/Error.h>
#include <mvcl/core/Export.h>
#include <mvcl/io/SessionFile.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace mvcl {

class MVCL_EXPORT RecoveryWriter {
public:
    using Clock = std::chrono::steady_clock;
    /// The session as a file holds it; called only when a write is due.
    using Describe = std::function<SessionDescription()>;
    static constexpr std::chrono::milliseconds kDefaultInterval{2000};

    /// `now` is the clock the interval is measured on (tests pass their own).
    explicit RecoveryWriter(std::function<Clock::time_point()> now = Clock::now);

    /// Where the copy goes; empty: nowhere (changes are still tracked, and written once a path
    /// is set).
    void setPath(const std::filesystem::path &file);
    const std::filesystem::path &path() const { return m_path; }
    /// The least time between two writes. Zero writes every change at once.
    void setInterval(std::chrono::milliseconds interval);
    std::chrono::milliseconds interval() const { return m_interval; }

    /// The session changed: writes it now when the last write is interval() old, else later
    /// (update(), flush()). Throws mvcl::Error naming the file when the write fails; the change
    /// stays pending and is tried again at the next due time.
    void sessionChanged(const Describe &describe);
    /// Writes a pending change once interval() has passed since the last write. Cheap when
    /// nothing is pending.
    void update(const Describe &describe);
    /// sessionChanged() when `changed`, else update(), for an owner that reports instead of
    /// throwing: a failed write comes back as the error to show ("recovery copy not written:
    /// ..."), once; the same failure again, one interval later, comes back empty.
    std::optional<Error> pass(bool changed, const Describe &describe);
    /// Writes a pending change now, whatever the interval.
    void flush(const Describe &describe);
    /// Forgets a pending change and removes the copy (no error when there is none).
    void discard();
    /// Forgets a pending change and leaves the copy as it is (the session was just loaded).
    void clearPending() { m_pending = false; }

    /// A change not yet written.
    bool isPending() const { return m_pending; }
    /// Writes done so far (tests, benchmarks).
    int writeCount() const { return m_writes; }

private:
    bool isDue() const;
    void write(const Describe &describe);

    std::function<Clock::time_point()> m_now;
    std::filesystem::path m_path;
    std::chrono::milliseconds m_interval = kDefaultInterval;
    Clock::time_point m_lastWrite;
    bool m_hasWritten = false;
    bool m_pending = false;
    int m_writes = 0;
    std::string m_lastError; ///< what pass() last reported
};

} // namespace mvcl
