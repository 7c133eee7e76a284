#pragma once
// Private: an allocator for the large per-pixel buffers of a render session. A fresh 800 × 600
// session touches ~20 MB of sums, estimates and priorities in its first pass; in 4 KiB pages
// that is ~5,000 page faults, which on a virtual machine cost more than the pass's shading
// (docs/benchmarks.md). Buffers of 1 MiB or more get their own 2 MiB-aligned mapping (rounded up to whole huge pages), marked for
// transparent huge pages (Linux, where the system allows them on request): a few dozen faults.
// Smaller buffers, and other systems, use operator new.

#include <cstddef>

namespace mvcl::detail {

void *allocateLargeBuffer(std::size_t bytes);
void freeLargeBuffer(void *p, std::size_t bytes) noexcept;

template <class T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U> &) noexcept {}
    T *allocate(std::size_t n) { return static_cast<T *>(allocateLargeBuffer(n * sizeof(T))); }
    void deallocate(T *p, std::size_t n) noexcept { freeLargeBuffer(p, n * sizeof(T)); }
    template <class U>
    bool operator==(const HugePageAllocator<U> &) const noexcept {
        return true;
    }
};

} // namespace mvcl::detail
