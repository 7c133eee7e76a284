#pragma once
// Private: the tracer's kernels per instruction set, as tables of plain function pointers.
//
// Each table is defined by the one translation unit compiled for its instruction set
// (TraversalSse2.cpp, TraversalAvx2.cpp, PacketAvx2.cpp, PacketAvx512.cpp, BvhBuildAvx2.cpp; the
// flags are in framework/CMakeLists.txt), as constant data: the program never runs a line of an
// extension's unit before KernelDispatch.cpp has checked that the CPU has that extension. A
// Tracer picks its tables once, when it is made; a BVH build picks its table when it starts.
// The entries take only types that are the same in every unit (KernelIsa.h).

#include "KernelIsa.h"

#include <cstddef>
#include <cstdint>

namespace mvcl {
struct Hit;
struct Ray;
struct RayQuery;
} // namespace mvcl

namespace mvcl::detail {

struct BinStorage;
struct Binner;
struct BuildPrim;
class LayerPriorityHit;
class NearestHit;
struct PacketSetup;
struct PlaneRecord;
struct RangeBounds;
struct RayContext;
struct UnusedBests;
struct WideBvh;
template <class Best>
struct PacketBests;

/// The single-ray walk of the wide BVH (WideTraversal.inl), one entry per closest-hit state.
struct SingleRayKernels {
    const char *name; ///< what Tracer::singleRayIsa() reports
    /// A whole closest-hit query over the planes [planes, planes + planeCount) and the BVH, under
    /// `query` with the range [tMin, tMax] (valid: isValidQuery()): its RayContext and closest-hit
    /// state made in the kernel's own instruction set, the result resolved into `hit`; true if
    /// there is one. queryLayered is for queries that reach two layers or more (LayerPriorityHit
    /// with `contactWindow`), queryNearest for the others (NearestHit).
    bool (*queryNearest)(const WideBvh &wide, const PlaneRecord *planes, std::size_t planeCount, const Ray &ray,
                         const RayQuery &query, float tMin, float tMax, Hit &hit);
    bool (*queryLayered)(const WideBvh &wide, const PlaneRecord *planes, std::size_t planeCount, const Ray &ray,
                         const RayQuery &query, float tMin, float tMax, float contactWindow, Hit &hit);
    /// Any hit: true on the first accepted hit (`unused` is only there for the type).
    bool (*occluded)(const WideBvh &wide, const RayContext &c, NearestHit &unused);
};

/// The packet walk (PacketTraversal.inl) over the rays `lanes` of a packet: closest hit returns
/// the rays whose result changed, any hit the rays that are occluded.
struct PacketKernels {
    const char *name; ///< what Tracer::packetIsa() reports
    /// The packet's entry: the `count` rays (at most 16) of s.rays into the lanes of s.p, with
    /// each ray's range end (s.tMax; `rayTMax`: null, or each ray's own upper bound),
    /// validity (isValidQuery) and dominant axis (WatertightRay::kz), every lane at once.
    void (*load)(PacketSetup &s, std::size_t count, const float *rayTMax);
    unsigned (*closestNearest)(const WideBvh &wide, unsigned lanes, PacketSetup &s, PacketBests<NearestHit> &best);
    unsigned (*closestLayered)(const WideBvh &wide, unsigned lanes, PacketSetup &s,
                               PacketBests<LayerPriorityHit> &best);
    unsigned (*occluded)(const WideBvh &wide, unsigned lanes, PacketSetup &s, UnusedBests &unused);
};

/// The BVH build's binning with SAH sweep and its partition (BvhBuild.h), where a faster variant
/// than the SSE2 code of BvhBuilder.cpp exists; both build the same tree bit for bit. The
/// builder runs these on its threads: how a node's bins are split between tasks stays with it.
struct BuildKernels {
    /// Bins [begin, end) and lowers bestCost to the cheapest split, setting bestAxis and
    /// bestSplit, as Builder::findSplit() does on one thread.
    void (*findSplit)(const Binner &binner, const BuildPrim *prims, uint32_t begin, uint32_t end, int &bestAxis,
                      int &bestSplit, double &bestCost);
    /// For a node binned as two tasks: makes in `out` the bins of [begin, end).
    void (*bin)(const Binner &binner, const BuildPrim *prims, uint32_t begin, uint32_t end, BinStorage &out);
    /// Adds the bins of `other` to those of `all` (exact).
    void (*merge)(BinStorage &all, const BinStorage &other, int nBins);
    /// The SAH sweep over the merged bins, with findSplit's result.
    void (*sweep)(const Binner &binner, const BinStorage &bins, int &bestAxis, int &bestSplit, double &bestCost);
    /// Partitions [begin, end) by bin (≤ split goes left) and returns where the right side
    /// starts, with both sides' bounds, as Builder::partition() does.
    uint32_t (*partition)(const Binner &binner, int axis, int split, BuildPrim *prims, uint32_t begin,
                          uint32_t end, RangeBounds &left, RangeBounds &right);
};

// The tables, each defined by its unit; null when this build has no such variant: a target other
// than x86-64, where CMake adds no -m flags, or a build that does not optimise for speed
// (MVCL_EXTENSION_KERNELS, KernelIsa.h).
extern const SingleRayKernels *const kSingleRayKernelsBaseline; ///< never null
extern const SingleRayKernels *const kSingleRayKernelsAvx2;
extern const PacketKernels *const kPacketKernelsAvx2;
extern const PacketKernels *const kPacketKernelsAvx512;
extern const BuildKernels *const kBuildKernelsAvx2;

/// The single-ray table for a Tracer made now: AVX2 when built and the CPU has it, unless a
/// test forces the baseline (TraversalIsa.h).
const SingleRayKernels &singleRayKernels();
/// The packet table for a Tracer made now, within the limit tests set; null when packets go ray
/// by ray (no AVX2).
const PacketKernels *packetKernels();
/// The faster build passes for a build started now; null for Builder's SSE2 ones.
const BuildKernels *buildKernels();

} // namespace mvcl::detail
