// The baseline single-ray traversal: each wide node's eight boxes as two 4-lane SSE halves
// (WideTraversal.inl), what every x86-64 CPU runs. Compiled with the library's flags only; its
// kernels share the isa_baseline namespace with the rest of the library (KernelIsa.h).

#include "KernelTables.h"
#include "LayerPriorityHit.h"
#include "NearestHit.h"

#define MVCL_TRAVERSAL_AVX2 0
#include "WideTraversal.inl"

namespace mvcl::detail {

namespace {
// The walk's instances themselves, no wrapper: a call less per query.
constinit const SingleRayKernels kTable{"sse2", queryNearest, queryLayered, anyHitWalk};
} // namespace

constinit const SingleRayKernels *const kSingleRayKernelsBaseline = &kTable;

} // namespace mvcl::detail
