#pragma once
/// \file ConvergenceCurves.h
/// Error-against-time curves of `mvcl-bench convergence`: where a curve first reaches a given
/// error (interpolated log-log, the way the curves are plotted).

#include <optional>
#include <vector>

namespace mvcl::bench {

struct CurvePoint {
    double seconds = 0.0;
    double error = 0.0;
};
using Curve = std::vector<CurvePoint>;

struct Crossing {
    double seconds = 0.0;
    /// The curve's first point is already at or below the target: `seconds` is that point's
    /// time, an upper bound (nothing before the first point is known).
    bool atFirstPoint = false;
};

/// The time at which the curve first reaches `target` (error ≤ target), interpolating linearly
/// in (log seconds, log error) between the last point above and the first point at or below.
/// nullopt when no point reaches it. Errors and times must be positive for the interpolation;
/// a zero error counts as reached, interpolated linearly instead.
std::optional<Crossing> firstCrossing(const Curve &curve, double target);

} // namespace mvcl::bench
