#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal or forced on.

#include <chrono>
#include <string>

namespace mvcl::cli {

class ProgressBar {
public:
    explicit ProgressBar(bool enabled);
    void update(float fraction);
    /// Text after the bar, e.g. "frame 3/60"; shown from the next update on.
    void setLabel(std::string label);
    void finish();

private:
    bool m_enabled;
    int m_lastPercent = -1;
    std::string m_label;
    bool m_labelChanged = false;
    std::chrono::steady_clock::time_point m_start;
};

} // namespace mvcl::cli
