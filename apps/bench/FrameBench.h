#pragma once
/// \file FrameBench.h
/// `mvcl-bench frame`: a whole frame as mvcl-render renders it (scene, camera, lens stack), its
/// rays by kind, and the rate of tracing the very same rays again with no shading (the tracer's
/// calls recorded with a TracerQueryLog and replayed): how close the frame comes to its
/// traversal bound.

namespace mvcl::bench {

/// argv[0] is "frame"; the rest are its options. Returns the process exit code.
int runFrameBench(int argc, char **argv);

} // namespace mvcl::bench
