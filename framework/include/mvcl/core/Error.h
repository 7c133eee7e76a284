#pragma once
/// \file Error.h
/// The one exception type of mvcl: configuration errors, bad input files, API misuse.
/// The render path never throws.

#include <mvcl/core/Export.h>

#include <stdexcept>
#include <string>

namespace mvcl {

/// An error a user can act on. `what()` is one line: "<source>: <problem>".
class MVCL_EXPORT Error : public std::runtime_error {
public:
    /// \param source the file, plugin or option the problem is in (may be empty)
    /// \param problem what is wrong, phrased for the user
    Error(std::string source, const std::string &problem)
        : std::runtime_error(source.empty() ? problem : source + ": " + problem),
          m_source(std::move(source)), m_problem(problem) {}

    const std::string &source() const { return m_source; }
    const std::string &problem() const { return m_problem; }

private:
    std::string m_source;
    std::string m_problem;
};

} // namespace mvcl
