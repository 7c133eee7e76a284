#include <mvcl/view/ConvergenceLog.h>

#include <mvcl/core/Error.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace mvcl {

struct ConvergenceLog::Private {
    std::filesystem::path path;
    std::ofstream out;
    int passes = 0;
    double milliseconds = 0.0;
    uint64_t samples = 0;
    uint64_t rays = 0;

    void check() const {
        if (!out) throw Error(path.string(), "cannot write the convergence log");
    }
};

ConvergenceLog::ConvergenceLog(const std::filesystem::path &path) : d(std::make_unique<Private>()) {
    d->path = path;
    d->out.open(path, std::ios::out | std::ios::trunc);
    if (!d->out)
        throw Error(path.string(), std::string("cannot write the convergence log: ") + std::strerror(errno));
    d->out << kHeader << '\n';
    d->out.flush();
    d->check();
}

ConvergenceLog::~ConvergenceLog() = default;

void ConvergenceLog::addPass(const RenderPassStats &pass, const ConvergenceStats &reached) {
    d->milliseconds += pass.milliseconds;
    d->samples += pass.samples;
    d->rays += pass.rays.total();
    ++d->passes;
    char row[512];
    // %.6g keeps what the plots need and reads back exactly enough; an estimate not yet made
    // (a pixel with one sample) is an empty field, not a number.
    char estimate[32] = "";
    if (reached.estimatedRelativeMse) std::snprintf(estimate, sizeof estimate, "%.6g", *reached.estimatedRelativeMse);
    std::snprintf(row, sizeof row, "%d,%s,%.6f,%llu,%llu,%.6g,%d,%d,%s,%.6g,%.6g,%llu\n", d->passes,
                  passKindName(pass.kind), d->milliseconds * 1e-3, static_cast<unsigned long long>(d->samples),
                  static_cast<unsigned long long>(d->rays), reached.meanSamples, reached.minSamples,
                  reached.maxSamples, estimate, reached.meanError, reached.maxError,
                  static_cast<unsigned long long>(reached.activePixels));
    d->out << row;
    d->out.flush();
    d->check();
}

int ConvergenceLog::passCount() const { return d->passes; }

} // namespace mvcl
