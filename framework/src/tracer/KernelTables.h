#pragma once
// Private: the tracer's kernels per instruction set, as tables of plain function pointers.
//
// Each table is defined by the one translation unit compiled for its instruction set
// (TraversalSse2.cpp, TraversalAvx2.cpp, PacketAvx2.cpp, PacketAvx512.cpp; the flags are in
// framework/CMakeLists.txt), as constant data: the program never runs a line of an
// extension's unit before KernelDispatch.cpp has checked that the CPU has that extension. A
// Tracer picks its tables once, when it is made.
// The entries take only types that are the same in every unit (KernelIsa.h).

#include <cstdint>

namespace mvcl::detail {

class LayerPriorityHit;
class NearestHit;
struct PacketSetup;
struct RayContext;
struct UnusedBests;
struct WideBvh;
template <class Best>
struct PacketBests;

/// The single-ray walk of the wide BVH (WideTraversal.inl), one entry per closest-hit state.
struct SingleRayKernels {
    const char *name; ///< what Tracer::singleRayIsa() reports
    /// Closest hit: offers every candidate to `best`; true if it changed.
    bool (*closestNearest)(const WideBvh &wide, const RayContext &c, NearestHit &best);
    bool (*closestLayered)(const WideBvh &wide, const RayContext &c, LayerPriorityHit &best);
    /// Any hit: true on the first accepted hit (`unused` is only there for the type).
    bool (*occluded)(const WideBvh &wide, const RayContext &c, NearestHit &unused);
};

/// The packet walk (PacketTraversal.inl) over the rays `lanes` of a packet: closest hit returns
/// the rays whose result changed, any hit the rays that are occluded.
struct PacketKernels {
    const char *name; ///< what Tracer::packetIsa() reports
    unsigned (*closestNearest)(const WideBvh &wide, unsigned lanes, PacketSetup &s, PacketBests<NearestHit> &best);
    unsigned (*closestLayered)(const WideBvh &wide, unsigned lanes, PacketSetup &s,
                               PacketBests<LayerPriorityHit> &best);
    unsigned (*occluded)(const WideBvh &wide, unsigned lanes, PacketSetup &s, UnusedBests &unused);
};

// The tables, each defined by its unit; null when this build has no such variant (a target other
// than x86-64, where CMake adds no -m flags and the unit compiles to this null pointer).
extern const SingleRayKernels *const kSingleRayKernelsBaseline; ///< never null
extern const SingleRayKernels *const kSingleRayKernelsAvx2;
extern const PacketKernels *const kPacketKernelsAvx2;
extern const PacketKernels *const kPacketKernelsAvx512;

/// The single-ray table for a Tracer made now: AVX2 when built and the CPU has it, unless a
/// test forces the baseline (TraversalIsa.h).
const SingleRayKernels &singleRayKernels();
/// The packet table for a Tracer made now, within the limit tests set; null when packets go ray
/// by ray (no AVX2).
const PacketKernels *packetKernels();

} // namespace mvcl::detail
