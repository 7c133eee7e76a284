// The AVX-512 packet traversal: the 16 rays of a packet in one 512-bit register (PacketTraversal.inl).
// framework/CMakeLists.txt compiles this file with -mavx512f; nothing here runs unless
// KernelDispatch.cpp found AVX-512F on the CPU, and every function it compiles is in namespace
// isa_avx512 (KernelIsa.h), compiled by no other unit.

#define MVCL_ISA_NAMESPACE isa_avx512

#include "KernelTables.h"

#if defined(__AVX512F__) && MVCL_EXTENSION_KERNELS

#include "LayerPriorityHit.h"
#include "NearestHit.h"

#define MVCL_PACKET_AVX512 1
#include "PacketTraversal.inl"

namespace mvcl::detail {

namespace {
unsigned closestNearest(const WideBvh &wide, unsigned lanes, PacketSetup &s, PacketBests<NearestHit> &best) {
    return tracePacket<false>(wide, lanes, s, best);
}
unsigned closestLayered(const WideBvh &wide, unsigned lanes, PacketSetup &s, PacketBests<LayerPriorityHit> &best) {
    return tracePacket<false>(wide, lanes, s, best);
}
unsigned occluded(const WideBvh &wide, unsigned lanes, PacketSetup &s, UnusedBests &unused) {
    return tracePacket<true>(wide, lanes, s, unused);
}

constinit const PacketKernels kTable{"avx512", closestNearest, closestLayered, occluded};
} // namespace

constinit const PacketKernels *const kPacketKernelsAvx512 = &kTable;

} // namespace mvcl::detail

#elif defined(__x86_64__) && MVCL_EXTENSION_KERNELS
#error "framework/CMakeLists.txt compiles this unit with -mavx512f on x86-64"
#else // not built for AVX-512 (not an x86-64 target, or not optimised for speed): no such variant

namespace mvcl::detail {
constinit const PacketKernels *const kPacketKernelsAvx512 = nullptr;
} // namespace mvcl::detail

#endif
