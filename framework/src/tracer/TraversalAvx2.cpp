// The AVX2 single-ray traversal: each wide node's eight boxes in one 256-bit test
// (WideTraversal.inl). framework/CMakeLists.txt compiles this file, and only this one of the
// single-ray kernels, with -mavx2; nothing here runs unless KernelDispatch.cpp found AVX2 on the
// CPU, and every function it compiles is in namespace isa_avx2 (KernelIsa.h).

#define MVCL_ISA_NAMESPACE isa_avx2

#include "KernelTables.h"

#if defined(__AVX2__) && MVCL_EXTENSION_KERNELS

#include "LayerPriorityHit.h"
#include "NearestHit.h"

#define MVCL_TRAVERSAL_AVX2 1
#include "WideTraversal.inl"

namespace mvcl::detail {

namespace {
// The walk's instances themselves, no wrapper: a call less per query.
constinit const SingleRayKernels kTable{"avx2", queryNearest, queryLayered, anyHitWalk};
} // namespace

constinit const SingleRayKernels *const kSingleRayKernelsAvx2 = &kTable;

} // namespace mvcl::detail

#elif defined(__x86_64__) && MVCL_EXTENSION_KERNELS
#error "framework/CMakeLists.txt compiles this unit with -mavx2 on x86-64"
#else // not built for AVX2 (not an x86-64 target, or not optimised for speed): no such variant

namespace mvcl::detail {
constinit const SingleRayKernels *const kSingleRayKernelsAvx2 = nullptr;
} // namespace mvcl::detail

#endif
