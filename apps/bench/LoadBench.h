#pragma once
/// \file LoadBench.h
/// `mvcl-bench load`: how fast model files are read (MB/s, triangles/s), and `--generate N DIR`,
/// a closed mesh of about N triangles written as binary STL, binary PLY and OBJ to measure with.

namespace mvcl::bench {

/// argv[0] is "load"; the rest are its options. Returns the process exit code.
int runLoadBench(int argc, char **argv);

} // namespace mvcl::bench
