#include "HugePageAllocator_p.h"

#include <algorithm>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mvcl::detail {

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;
/// From this size on a buffer gets huge pages: an 800 × 600 image's floats (1.9 MB) are just
/// below one, and rounding them up costs less than their 470 small pages' faults.
constexpr std::size_t kLargeBuffer = std::size_t(1) << 20;
/// Cache-line alignment for every other buffer: no element straddles more lines than it must.
constexpr std::size_t kLine = 64;

std::size_t roundUp(std::size_t bytes, std::size_t to) { return (bytes + to - 1) / to * to; }

} // namespace

void *allocateLargeBuffer(std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= kLargeBuffer) {
        // Whole aligned 2 MiB ranges: the kernel backs only those with huge pages.
        const std::size_t size = roundUp(bytes, kHugePage);
        void *p = std::aligned_alloc(kHugePage, size);
        if (!p) throw std::bad_alloc();
        madvise(p, size, MADV_HUGEPAGE); // advice only: without huge pages the buffer works in small ones
        return p;
    }
#endif
    void *p = std::aligned_alloc(kLine, roundUp(std::max<std::size_t>(bytes, 1), kLine));
    if (!p) throw std::bad_alloc();
    return p;
}

void freeLargeBuffer(void *p) noexcept { std::free(p); }

} // namespace mvcl::detail
