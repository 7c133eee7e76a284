#pragma once
/// \file AlternatingRuns.h
/// How mvcl-bench compares two tracers on a machine shared with other work: each run times one
/// tracer over all the rays, the two alternate run by run (who goes first alternates too), so a
/// neighbour's load falls on both; the rows print the best and median run, the spread, and the
/// ratios of the runs taken back to back, by wall clock and by process CPU time.

#include "BenchSupport.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <time.h>
#include <vector>

namespace mvcl::bench {

/// CPU time of the whole process (every thread), in seconds.
inline double processCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// Wall times (`seconds`) and process CPU times (`cpuSeconds`) of the runs of one side. On a
/// machine shared with other builds the CPU time is the steadier measure: time the process
/// spends descheduled does not count.
struct Runs {
    std::vector<double> seconds;
    std::vector<double> cpuSeconds;
    double best() const { return *std::min_element(seconds.begin(), seconds.end()); }
    double worst() const { return *std::max_element(seconds.begin(), seconds.end()); }
    double median() const {
        std::vector<double> s = seconds;
        std::sort(s.begin(), s.end());
        return s.size() % 2 ? s[s.size() / 2] : 0.5 * (s[s.size() / 2 - 1] + s[s.size() / 2]);
    }
};

/// `repeat` runs of each, alternating, the first side alternating too.
template <class Ours, class Peer>
inline void alternate(int repeat, bool withPeer, const Ours &ours, const Peer &peer, Runs &oursRuns, Runs &peerRuns) {
    auto time = [](const auto &f, Runs &runs) {
        const double cpuStart = processCpuSeconds();
        const auto start = Clock::now();
        f();
        runs.seconds.push_back(secondsSince(start));
        runs.cpuSeconds.push_back(processCpuSeconds() - cpuStart);
    };
    for (int r = 0; r < repeat; ++r) {
        if (withPeer && r % 2) time(peer, peerRuns);
        time(ours, oursRuns);
        if (withPeer && !(r % 2)) time(peer, peerRuns);
    }
}

/// The CPU-time view of the same runs.
inline Runs cpuView(const Runs &runs) {
    Runs cpu;
    cpu.seconds = runs.cpuSeconds;
    return cpu;
}

/// "rate (best), median, [slowest run .. fastest run]" of n rays, by wall clock and CPU time.
inline void printRate(const char *side, std::size_t n, const Runs &runs) {
    auto line = [&](const char *clock, const Runs &r) {
        std::printf("  %-7s %-4s %9.3f Mrays/s best, %9.3f median, runs %.3f..%.3f\n", side, clock,
                    double(n) / r.best() * 1e-6, double(n) / r.median() * 1e-6, double(n) / r.worst() * 1e-6,
                    double(n) / r.best() * 1e-6);
    };
    line("wall", runs);
    line("cpu", cpuView(runs));
}

/// Ratio of the best runs, of the medians, and the range of the ratios of the runs paired in time.
inline void printRatio(const Runs &ours, const Runs &peer) {
    auto line = [](const char *clock, const Runs &o, const Runs &p) {
        double lo = 1e300, hi = 0.0;
        for (std::size_t r = 0; r < o.seconds.size(); ++r) {
            const double ratio = p.seconds[r] / o.seconds[r];
            lo = std::min(lo, ratio);
            hi = std::max(hi, ratio);
        }
        std::printf("  ratio ours/embree %-4s %.3f (best runs), median %.3f, run pairs %.3f..%.3f\n", clock,
                    p.best() / o.best(), p.median() / o.median(), lo, hi);
    };
    line("wall", ours, peer);
    line("cpu", cpuView(ours), cpuView(peer));
}

} // namespace mvcl::bench
