// Which instruction set's kernels run: the CPU's widest that this build has, unless a test
// narrows the choice (TraversalIsa.h). Baseline code, like everything outside the kernel units:
// it must run on any x86-64 CPU to find out what else may run.

#include "KernelTables.h"
#include "TraversalIsa.h"

#include <algorithm>
#include <atomic>

namespace mvcl::detail {

namespace {

// Set by tests (TraversalIsa.h).
std::atomic<bool> g_forceSseTraversal{false};
std::atomic<bool> g_forceSseBinning{false};
std::atomic<PacketIsa> g_packetIsaLimit{PacketIsa::Avx512};

// __builtin_cpu_supports (GCC and clang) also checks that the OS saves the wider registers.
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
bool cpuHasAvx2() { return __builtin_cpu_supports("avx2"); }
bool cpuHasAvx512() { return __builtin_cpu_supports("avx512f"); }
#else
bool cpuHasAvx2() { return false; }
bool cpuHasAvx512() { return false; }
#endif

} // namespace

void forceSseTraversal(bool force) { g_forceSseTraversal.store(force); }
void forceSseBinning(bool force) { g_forceSseBinning.store(force); }
void limitPacketIsa(PacketIsa isa) { g_packetIsaLimit.store(isa); }

bool avx2TraversalAvailable() { return kSingleRayKernelsAvx2 && cpuHasAvx2(); }

PacketIsa packetIsaAvailable() {
    if (kPacketKernelsAvx512 && cpuHasAvx512()) return PacketIsa::Avx512;
    if (kPacketKernelsAvx2 && cpuHasAvx2()) return PacketIsa::Avx2;
    return PacketIsa::SingleRays;
}

const SingleRayKernels &singleRayKernels() {
    return !g_forceSseTraversal.load() && avx2TraversalAvailable() ? *kSingleRayKernelsAvx2
                                                                  : *kSingleRayKernelsBaseline;
}

const PacketKernels *packetKernels() {
    switch (std::min(packetIsaAvailable(), g_packetIsaLimit.load())) {
    case PacketIsa::Avx512: return kPacketKernelsAvx512;
    case PacketIsa::Avx2: return kPacketKernelsAvx2;
    case PacketIsa::SingleRays: break;
    }
    return nullptr;
}

const BuildKernels *buildKernels() {
    return kBuildKernelsAvx2 && cpuHasAvx2() && !g_forceSseBinning.load() ? kBuildKernelsAvx2 : nullptr;
}

} // namespace mvcl::detail
