#pragma once
// Private: which compiled variant of the wide-BVH traversal a Tracer uses (WideTraversal.inl).
// A Tracer picks AVX2 when the CPU has it; tests force the SSE baseline to check that both give
// bit-identical results.

namespace mvcl::detail {

/// Forces (or stops forcing) the SSE traversal for Tracers constructed afterwards.
void forceSseTraversal(bool force);

/// True if this build has the AVX2 traversal and the CPU supports it.
bool avx2TraversalAvailable();

} // namespace mvcl::detail
