#pragma once
// Private: which compiled variant of the wide-BVH traversal a Tracer uses (WideTraversal.inl).
// A Tracer picks AVX2 when the CPU has it; tests force the SSE baseline to check that both give
// bit-identical results. Packets likewise: AVX-512 or AVX2, limited by tests to check each. The
// BVH build's binning too: AVX2 or SSE2, which must build the same tree. The choice itself is made
// in KernelDispatch.cpp, among the tables of KernelTables.h.

namespace mvcl::detail {

/// Forces (or stops forcing) the SSE traversal for Tracers constructed afterwards.
void forceSseTraversal(bool force);

/// Forces (or stops forcing) the SSE2 binning, SAH sweep and partition of BVH builds started
/// afterwards; the AVX2 ones must build the same tree (tests compare them).
void forceSseBinning(bool force);

/// True if this build has the AVX2 traversal and the CPU supports it.
bool avx2TraversalAvailable();

/// The packet traversal variants, from none (packets traced ray by ray) to the widest.
enum class PacketIsa { SingleRays, Avx2, Avx512 };
/// The widest variant this build has and the CPU supports.
PacketIsa packetIsaAvailable();
/// Tracers constructed afterwards use at most `isa` for packets (tests check every variant
/// against single rays); PacketIsa::Avx512 lifts the limit.
void limitPacketIsa(PacketIsa isa);

} // namespace mvcl::detail
