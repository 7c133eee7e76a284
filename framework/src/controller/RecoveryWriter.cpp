#include <mvcl/controller/RecoveryWriter.h>

#include <algorithm>
#include <system_error>
#include <utility>

namespace mvcl {

RecoveryWriter::RecoveryWriter(std::function<Clock::time_point()> now) : m_now(std::move(now)) {}

void RecoveryWriter::setPath(const std::filesystem::path &file) { m_path = file; }

void RecoveryWriter::setInterval(std::chrono::milliseconds interval) {
    m_interval = std::max(interval, std::chrono::milliseconds(0));
}

bool RecoveryWriter::isDue() const { return !m_hasWritten || m_now() - m_lastWrite >= m_interval; }

void RecoveryWriter::sessionChanged(const Describe &describe) {
    m_pending = true;
    if (isDue()) write(describe);
}

void RecoveryWriter::update(const Describe &describe) {
    if (m_pending && isDue()) write(describe);
}

std::optional<Error> RecoveryWriter::pass(bool changed, const Describe &describe) {
    try {
        if (changed) sessionChanged(describe);
        else update(describe);
        m_lastError.clear();
        return std::nullopt;
    } catch (const Error &e) {
        Error error(e.source(), "recovery copy not written: " + e.problem());
        if (error.what() == m_lastError) return std::nullopt; // tried again one interval later: said already
        m_lastError = error.what();
        return error;
    }
}

void RecoveryWriter::flush(const Describe &describe) {
    if (m_pending) write(describe);
}

void RecoveryWriter::discard() {
    m_pending = false;
    if (m_path.empty()) return;
    std::error_code ec;
    std::filesystem::remove(m_path, ec); // a copy that is not there is what we want
}

void RecoveryWriter::write(const Describe &describe) {
    if (m_path.empty()) return; // stays pending until there is somewhere to write
    // The time is taken before writing: a failed write is tried again one interval later, not
    // at every change.
    m_lastWrite = m_now();
    m_hasWritten = true;
    writeSessionFile(m_path, describe());
    m_pending = false;
    ++m_writes;
}

} // namespace mvcl
