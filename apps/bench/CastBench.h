#pragma once
/// \file CastBench.h
/// `mvcl-bench cast`: one primary ray per pixel centre of a given camera (CastRays.h), cast with
/// our tracer (and Embree's rtcIntersect1 with --peer), printing what another tracer needs to
/// check us on identical rays: the hit count, the sum of the hit distances, the ray rate.

namespace mvcl::bench {

/// argv[0] is "cast"; the rest are its options. Returns the process exit code.
int runCastBench(int argc, char **argv);

} // namespace mvcl::bench
