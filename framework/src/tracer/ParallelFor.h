#pragma once
// Private: the tracer build's minimal parallel loop. Work items are independent and each writes
// its own output, so the result never depends on which thread ran which item.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace mvcl::detail {

/// Runs f(i) for every i in [0, n) on up to `threads` threads (the caller's included), items
/// handed out one at a time: callers make items coarse (subtrees, chunks of thousands).
template <class F>
void parallelFor(std::size_t n, int threads, const F &f) {
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < n;) f(i);
    };
    std::vector<std::thread> pool;
    const std::size_t helpers = std::min<std::size_t>(std::size_t(std::max(threads, 1)), n);
    for (std::size_t t = 1; t < helpers; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread &t : pool) t.join();
}

} // namespace mvcl::detail
