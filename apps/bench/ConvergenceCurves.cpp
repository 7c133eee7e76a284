#include "ConvergenceCurves.h"

#include <cmath>

namespace mvcl::bench {

std::optional<Crossing> firstCrossing(const Curve &curve, double target) {
    for (std::size_t i = 0; i < curve.size(); ++i) {
        if (!(curve[i].error <= target)) continue;
        if (i == 0) return Crossing{curve[0].seconds, true};
        const CurvePoint &a = curve[i - 1], &b = curve[i];
        // a is above the target and b at or below it, so a.error > b.error and the fraction
        // lies in (0, 1].
        const bool logLog = a.seconds > 0.0 && b.seconds > 0.0 && b.error > 0.0 && target > 0.0;
        const double f = logLog ? std::log(a.error / target) / std::log(a.error / b.error)
                                : (a.error - target) / (a.error - b.error);
        const double seconds = logLog ? a.seconds * std::pow(b.seconds / a.seconds, f)
                                      : a.seconds + f * (b.seconds - a.seconds);
        return Crossing{seconds, false};
    }
    return std::nullopt;
}

} // namespace mvcl::bench
