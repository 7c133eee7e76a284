// The AVX-512 packet traversal: the 16 rays of a packet in one 512-bit register
// (PacketTraversal.inl). framework/CMakeLists.txt compiles this file with -mavx512f; nothing here
// runs unless KernelDispatch.cpp found AVX-512F on the CPU, and every function it compiles is in
// namespace isa_avx512 (KernelIsa.h), compiled by no other unit.

#define MVCL_ISA_NAMESPACE isa_avx512

#include "KernelTables.h"

#if defined(__AVX512F__) && MVCL_EXTENSION_KERNELS

#include "LayerPriorityHit.h"
#include "NearestHit.h"

#define MVCL_PACKET_AVX512 1
#include "PacketTraversal.inl"

namespace mvcl::detail {

namespace {
// The entry and the walk's instances themselves, no wrapper: a call less per packet.
constinit const PacketKernels kTable{"avx512", loadPacket, tracePacket<false, PacketBests<NearestHit>>,
                                     tracePacket<false, PacketBests<LayerPriorityHit>>,
                                     tracePacket<true, UnusedBests>};
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
