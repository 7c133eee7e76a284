#include "ProgressBar.h"

#include <cstdio>
#include <string>

namespace mvcl::cli {

ProgressBar::ProgressBar(bool enabled) : m_enabled(enabled), m_start(std::chrono::steady_clock::now()) {}

void ProgressBar::update(float fraction) {
    if (!m_enabled) return;
    const int percent = int(fraction * 100.f);
    if (percent == m_lastPercent && !m_labelChanged) return;
    m_lastPercent = percent;
    m_labelChanged = false;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    constexpr int kWidth = 40;
    const int filled = percent * kWidth / 100;
    std::fprintf(stderr, "\r[%s%s] %3d%% %6.1fs %s", std::string(std::size_t(filled), '#').c_str(),
                 std::string(std::size_t(kWidth - filled), '.').c_str(), percent, seconds, m_label.c_str());
    std::fflush(stderr);
}

void ProgressBar::setLabel(std::string label) {
    m_labelChanged = label != m_label;
    m_label = std::move(label);
}

void ProgressBar::finish() {
    if (m_enabled && m_lastPercent >= 0) std::fprintf(stderr, "\n");
}

} // namespace mvcl::cli
