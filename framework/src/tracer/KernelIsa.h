#pragma once
// Private: how the tracer's kernels compiled for different instruction sets are kept apart.
//
// The kernels (wide-BVH traversal, leaf and triangle tests, packet traversal, the BVH build's
// binning and partition) are compiled once per instruction set, each copy in a translation unit
// of its own with its own -m flags (framework/CMakeLists.txt), and a table per unit hands them to
// the code that picks one at run time (KernelTables.h). Those units include the same headers. An
// inline function or template the compiler does not inline is emitted as a weak symbol in every
// object that uses it, and the linker keeps one of the copies, any one: were the AVX2 object's
// copy kept for a baseline caller, a CPU without AVX2 would fault on it. So:
//   - every kernel function sits in `inline namespace MVCL_ISA_NAMESPACE`: isa_avx2 in the units
//     compiled with -mavx2, isa_avx512 in the one compiled with -mavx512f, isa_baseline in every
//     other. Each such unit defines MVCL_ISA_NAMESPACE before its first include, next to the
//     code it selects, and framework/CMakeLists.txt gives the file the matching flags.
//     Copies for different instruction sets then have different symbols; callers still write
//     detail::testLeaf, the inline namespace being transparent to them;
//   - the types the tables pass between units (RayContext, the closest-hit states, PacketSetup,
//     the BVH build's records) are one type for every unit, outside that namespace, and their
//     member functions are MVCL_KERNEL_INLINE: always inlined, so no object has an out-of-line
//     copy of them to share.
// The IsaSymbols.* tests (tests/tracer/CheckIsaSymbols.cmake) check the result on the objects:
// no weak function defined by objects of two instruction sets, and no start-up code in the units
// of an extension (it would run before any CPU check).

#if !defined(MVCL_ISA_NAMESPACE)
#define MVCL_ISA_NAMESPACE isa_baseline
#endif

#if defined(__GNUC__)
#define MVCL_KERNEL_INLINE inline __attribute__((always_inline))
#else
#define MVCL_KERNEL_INLINE inline
#endif

// Where the compiler inlines little (-O0, -Os), small inline functions of the standard library
// and GLM that every kernel calls (std::unique_ptr::get, glm's operator[]) are emitted out of
// line in every unit, outside any kernel namespace, and could not be kept apart. So are they in
// the sanitizer builds (clang -O1 with ASan and UBSan and assertions on: glm's operator[] keeps
// its assertion and is not inlined; seen in IsaSymbols.* there). Such builds compile no extension
// kernels: those units give null tables and the baseline runs (KernelDispatch.cpp). The compiler
// does not tell -Og and -O1 apart from faster levels; IsaSymbols.* reports it if a build at
// those levels shares code between units.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MVCL_KERNELS_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define MVCL_KERNELS_SANITIZED 1
#endif
#endif
#if defined(__OPTIMIZE__) && !defined(__OPTIMIZE_SIZE__) && !defined(MVCL_KERNELS_SANITIZED)
#define MVCL_EXTENSION_KERNELS 1
#else
#define MVCL_EXTENSION_KERNELS 0
#endif
