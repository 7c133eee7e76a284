#include <mvcl/view/ConvergenceHistory.h>

#include <algorithm>
#include <cmath>

namespace mvcl {

void ConvergenceHistory::add(const ConvergenceStats &reached, uint64_t passCount) {
    if (m_hasPass && passCount == m_lastPass) return;
    m_hasPass = true;
    m_lastPass = passCount;
    if (!reached.estimatedRelativeMse || !(*reached.estimatedRelativeMse > 0.0)) return;
    if (!m_points.empty() && reached.elapsedSeconds < m_points.back().seconds) m_points.clear();
    m_points.push_back({reached.elapsedSeconds, *reached.estimatedRelativeMse, reached.meanSamples});
}

void ConvergenceHistory::clear() {
    m_points.clear();
    m_hasPass = false;
}

std::vector<float> ConvergenceHistory::log10ErrorOverTime(int bins) const {
    if (m_points.empty() || bins < 2) return {};
    std::vector<float> values(static_cast<size_t>(bins));
    const double end = m_points.back().seconds;
    size_t at = 0;
    for (int b = 0; b < bins; ++b) {
        const double t = end * double(b) / double(bins - 1);
        while (at + 1 < m_points.size() && m_points[at + 1].seconds <= t) ++at;
        values[size_t(b)] = float(std::log10(m_points[at].relativeMse));
    }
    return values;
}

} // namespace mvcl
