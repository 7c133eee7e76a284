#pragma once
/// \file ConvergenceLog.h
/// Error against time for any render, with no reference: a CSV file with one row after every
/// pass of a RenderSession (time, samples, rays and the session's own error estimates), for
/// `mvcl-render --convergence-log` and anyone who drives a session. `scripts/plot-convergence.py`
/// plots such a file.

#include <mvcl/core/Export.h>
#include <mvcl/view/RenderSession.h>

#include <filesystem>
#include <memory>

namespace mvcl {

class MVCL_EXPORT ConvergenceLog {
public:
    /// The columns, in order, as the file's first line names them.
    static constexpr const char *kHeader =
        "pass,kind,seconds,samples,rays,mean_spp,min_spp,max_spp,estimated_relmse,mean_error,max_error,"
        "active_pixels";

    /// Creates (or truncates) `path` and writes the header. Throws mvcl::Error(path, ...) when
    /// the file cannot be written, before anything is rendered.
    explicit ConvergenceLog(const std::filesystem::path &path);
    ~ConvergenceLog();
    ConvergenceLog(const ConvergenceLog &) = delete;
    ConvergenceLog &operator=(const ConvergenceLog &) = delete;

    /// Appends the state after a pass: `pass` is what RenderSession::renderPass() returned,
    /// `reached` the session's convergence() right after it. Time, samples and rays are summed
    /// over the passes added so far (the wall time of the passes only). The row is flushed, so an
    /// interrupted render leaves every row written so far. Throws mvcl::Error(path, ...) when a
    /// write fails.
    void addPass(const RenderPassStats &pass, const ConvergenceStats &reached);
    /// Rows added so far.
    int passCount() const;

private:
    struct MVCL_HIDDEN Private;
    std::unique_ptr<Private> d;
};

} // namespace mvcl
