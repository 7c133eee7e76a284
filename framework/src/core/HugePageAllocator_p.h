#pragma once
// Private: an allocator for the large per-pixel buffers of a render session. A fresh 800 × 600
// session touches ~20 MB of sums, estimates and priorities in its first pass; in 4 KiB pages
// that is ~5,000 page faults, which on a virtual machine cost more than the pass's shading
// (docs/benchmarks.md). Buffers of 1 MiB or more are 2 MiB-aligned and rounded up to whole huge
// pages, marked for transparent huge pages (Linux, where the system allows them on request): a
// few dozen faults. Smaller buffers, and other systems, are 64-byte aligned. The tracer's large
// arrays take the same memory (src/tracer/Bvh.h, allocateAligned).

#include <cstddef>

namespace mvcl::detail {

/// Not initialised; released with freeLargeBuffer (std::free).
void *allocateLargeBuffer(std::size_t bytes);
void freeLargeBuffer(void *p) noexcept;

template <class T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U> &) noexcept {}
    T *allocate(std::size_t n) { return static_cast<T *>(allocateLargeBuffer(n * sizeof(T))); }
    void deallocate(T *p, std::size_t) noexcept { freeLargeBuffer(p); }
    template <class U>
    bool operator==(const HugePageAllocator<U> &) const noexcept {
        return true;
    }
};

} // namespace mvcl::detail
