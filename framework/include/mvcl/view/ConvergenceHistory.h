#pragma once
/// \file ConvergenceHistory.h
/// The estimated error of a view's image against time since its last restart, for a live curve
/// (the viewer's stats panel): fed with RenderSession::convergence() whenever a pass ends, it
/// keeps one point per pass and starts over when the session restarts every pixel (camera,
/// size or seed changes).

#include <mvcl/core/Export.h>
#include <mvcl/view/RenderSession.h>

#include <cstdint>
#include <vector>

namespace mvcl {

class MVCL_EXPORT ConvergenceHistory {
public:
    struct Point {
        double seconds;      ///< ConvergenceStats::elapsedSeconds
        double relativeMse;  ///< ConvergenceStats::estimatedRelativeMse
        double meanSamples;
    };

    /// Adds the state after pass number `passCount` (RenderSession::passCount()); the same pass
    /// twice adds one point. A state whose time went back (the session restarted its pixels)
    /// starts a new curve. States without an estimate yet add nothing.
    void add(const ConvergenceStats &reached, uint64_t passCount);
    void clear();
    const std::vector<Point> &points() const { return m_points; }
    bool isEmpty() const { return m_points.empty(); }

    /// The curve as `bins` values of log10(relMSE), at times evenly spread over [0, last
    /// point's time]; each bin holds the error of the last point at or before its time (the
    /// first point's before it). Empty with no points or bins < 2.
    std::vector<float> log10ErrorOverTime(int bins) const;

private:
    std::vector<Point> m_points;
    uint64_t m_lastPass = 0;
    bool m_hasPass = false;
};

} // namespace mvcl
