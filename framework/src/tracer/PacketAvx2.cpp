// The AVX2 packet traversal: the 16 rays of a packet as two 8-lane halves (PacketTraversal.inl).
// framework/CMakeLists.txt compiles this file with -mavx2; nothing here runs unless
// KernelDispatch.cpp found AVX2 on the CPU, and every function it compiles is in namespace
// isa_avx2 (KernelIsa.h), shared only with TraversalAvx2.cpp, which has the same flags.

#define MVCL_ISA_NAMESPACE isa_avx2

#include "KernelTables.h"

#if defined(__AVX2__) && MVCL_EXTENSION_KERNELS

#include "LayerPriorityHit.h"
#include "NearestHit.h"

#define MVCL_PACKET_AVX512 0
#include "PacketTraversal.inl"

namespace mvcl::detail {

namespace {
// The entry and the walk's instances themselves, no wrapper: a call less per packet.
constinit const PacketKernels kTable{"avx2", loadPacket, tracePacket<false, PacketBests<NearestHit>>,
                                     tracePacket<false, PacketBests<LayerPriorityHit>>,
                                     tracePacket<true, UnusedBests>};
} // namespace

constinit const PacketKernels *const kPacketKernelsAvx2 = &kTable;

} // namespace mvcl::detail

#elif defined(__x86_64__) && MVCL_EXTENSION_KERNELS
#error "framework/CMakeLists.txt compiles this unit with -mavx2 on x86-64"
#else // not built for AVX2 (not an x86-64 target, or not optimised for speed): packets go ray by ray

namespace mvcl::detail {
constinit const PacketKernels *const kPacketKernelsAvx2 = nullptr;
} // namespace mvcl::detail

#endif
