#pragma once
/// \file PacketBench.h
/// The packet part of mvcl-bench: the primary rays in 4×4 tiles through Tracer::closestHits
/// against Embree's rtcIntersect16 (coherent flag), and the shadow rays of the same tiles
/// through Tracer::anyHits against rtcOccluded16, the two tracers alternating run by run.

#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/Tracer.h>

#include <vector>

#ifdef MVCL_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace mvcl::bench {

struct PacketBenchInput {
    const Tracer *tracer = nullptr;
#ifdef MVCL_HAVE_EMBREE
    RTCScene embree = nullptr; ///< null: our tracer only
#endif
    /// width × height primary rays in pixel order (row by row).
    const std::vector<Ray> *primary = nullptr;
    int width = 0, height = 0;
    RayQuery primaryQuery;
    /// Shadow rays and the pixel each starts from (ascending).
    const std::vector<Ray> *shadow = nullptr;
    const std::vector<int> *shadowPixel = nullptr;
    RayQuery shadowQuery;
    int threads = 1;
    int repeat = 3;
};

/// Measures and prints the packet rows (rates with their spread over the runs, per-run ratios,
/// the ISA of each side) and checks that the packets' hits are the single-ray hits bit for bit.
/// Returns false if they are not.
bool runPacketComparison(const PacketBenchInput &input);

#ifdef MVCL_HAVE_EMBREE
/// The ISA lines of Embree's verbose device report (what its kernels were built for and use).
std::string embreeIsaReport();
#endif

} // namespace mvcl::bench
