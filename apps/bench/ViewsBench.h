#pragma once
/// \file ViewsBench.h
/// `mvcl-bench views`: two views of one model in a Document, each at the given size: the BVH
/// built once and what the second view adds to the process's memory; a lens drag in one view
/// per UI frame while the other idles; an orbit of two views with linked cameras against one
/// view's orbit.

namespace mvcl::bench {

/// argv[0] is "views"; the rest are its options. Returns the process exit code.
int runViewsBench(int argc, char **argv);

} // namespace mvcl::bench
