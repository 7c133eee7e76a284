#include "HugePageAllocator_p.h"

#include <cstdint>
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

std::size_t roundUpToHugePages(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

} // namespace

void *allocateLargeBuffer(std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= kLargeBuffer) {
        // Map one huge page more than needed and keep the aligned part: the kernel backs only
        // whole aligned 2 MiB ranges with huge pages.
        const std::size_t size = roundUpToHugePages(bytes);
        void *raw = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (raw == MAP_FAILED) throw std::bad_alloc();
        const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(raw);
        const std::uintptr_t aligned = (begin + kHugePage - 1) / kHugePage * kHugePage;
        if (aligned > begin) munmap(raw, aligned - begin);
        if (const std::uintptr_t tail = begin + size + kHugePage - (aligned + size); tail > 0)
            munmap(reinterpret_cast<void *>(aligned + size), tail);
        // Advice only: without huge pages the buffer works in small ones.
        madvise(reinterpret_cast<void *>(aligned), size, MADV_HUGEPAGE);
        return reinterpret_cast<void *>(aligned);
    }
#endif
    return ::operator new(bytes);
}

void freeLargeBuffer(void *p, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= kLargeBuffer) {
        munmap(p, roundUpToHugePages(bytes));
        return;
    }
#endif
    ::operator delete(p);
}

} // namespace mvcl::detail
