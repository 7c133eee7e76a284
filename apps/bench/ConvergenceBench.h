#pragma once
/// \file ConvergenceBench.h
/// `mvcl-bench convergence`: error against wall time for uniform, progressive and adaptive
/// sampling of one scene, against a converged reference (docs/benchmarks.md, "Error against
/// run time").

namespace mvcl::bench {

/// argv[0] is "convergence"; the rest are its options. Returns the process exit code.
int runConvergenceBench(int argc, char **argv);

} // namespace mvcl::bench
