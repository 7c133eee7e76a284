// Proof, for scripts/ci-tsan.sh, that the ThreadSanitizer job sees what it must see, in both
// directions. Built only with MVCL_SANITIZE_THREAD.
//
//   mvcl-tsan-probe race    chunks of a worker-pool loop increment one shared counter without
//                           synchronisation: TSan must report a data race in racyIncrement.
//                           If it does not, the job cannot fail and proves nothing.
//   mvcl-tsan-probe clean   chunks write their own slots and the caller reads them after the
//                           loop: correct code, so no report. Against an uninstrumented oneTBB,
//                           TSan cannot see the pool hand the chunks over and back and reports
//                           this too: the probe fails then, which is how the job knows the
//                           oneTBB it links is the instrumented one.

#include <mvcl/core/WorkerPool.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

namespace {

// Out of line and named, so that the report's stack names it for the job to find.
[[gnu::noinline]] void racyIncrement(long *counter) { *counter = *counter + 1; }

int race() {
    long counter = 0;
    // Each item waits (up to 5 s) until a second thread has run an item, so that the race does
    // not depend on a worker waking up in time. Relaxed atomics: TSan sees no synchronisation in
    // them, so they do not order the racy increments.
    std::atomic<std::thread::id> first{};
    std::atomic<bool> secondThreadRan{false};
    mvcl::parallelFor(64, 2, [&](std::size_t) {
        racyIncrement(&counter);
        std::thread::id expected{};
        const std::thread::id me = std::this_thread::get_id();
        if (!first.compare_exchange_strong(expected, me, std::memory_order_relaxed) && expected != me)
            secondThreadRan.store(true, std::memory_order_relaxed);
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        while (!secondThreadRan.load(std::memory_order_relaxed) && std::chrono::steady_clock::now() < deadline)
            std::this_thread::yield();
    });
    std::printf("race: counter %ld (64 unless increments were lost), %s\n", counter,
                secondThreadRan.load() ? "two threads ran items" : "only one thread ran items: no race to see");
    return 0;
}

int clean() {
    std::vector<long> slots(4096, 0);
    mvcl::parallelForChunks(slots.size(), 0, 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) slots[i] = long(i) * 3;
    });
    long sum = 0;
    for (long value : slots) sum += value;
    std::printf("clean: sum %ld (expected %ld)\n", sum, 3L * 4095L * 4096L / 2L);
    return sum == 3L * 4095L * 4096L / 2L ? 0 : 1;
}

} // namespace

int main(int argc, char **argv) {
    if (argc == 2 && std::strcmp(argv[1], "race") == 0) return race();
    if (argc == 2 && std::strcmp(argv[1], "clean") == 0) return clean();
    std::fprintf(stderr, "usage: mvcl-tsan-probe race|clean\n");
    return 2;
}
