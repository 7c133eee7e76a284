#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal or forced on.

#include <chrono>

namespace mvcl::cli {

class ProgressBar {
public:
    explicit ProgressBar(bool enabled);
    void update(float fraction);
    void finish();

private:
    bool m_enabled;
    int m_lastPercent = -1;
    std::chrono::steady_clock::time_point m_start;
};

} // namespace mvcl::cli
