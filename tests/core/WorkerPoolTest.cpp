// The worker pool: every item of a loop runs exactly once, in chunks of at most the grain,
// whatever the thread count; nested loops share the pool without deadlocking; results written
// by the chunks are visible to the caller when the loop returns. Under ThreadSanitizer
// (scripts/ci-tsan.sh) these tests also check that the pool's hand-offs are seen.

#include <mvcl/core/WorkerPool.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <numeric>
#include <thread>
#include <vector>

namespace mvcl {
namespace {

TEST(WorkerPool, EveryItemRunsOnceInChunksOfAtMostTheGrain) {
    for (int threads : {0, 1, 2, 5})
        for (std::size_t grain : {std::size_t(1), std::size_t(7), std::size_t(64)}) {
            const std::size_t count = 1000;
            std::vector<int> visits(count, 0); // each chunk writes only its own items
            std::atomic<int> oversized{0};
            parallelForChunks(count, threads, grain, [&](std::size_t begin, std::size_t end) {
                if (end - begin > grain || begin >= end) ++oversized;
                for (std::size_t i = begin; i < end; ++i) ++visits[i];
            });
            EXPECT_EQ(oversized.load(), 0) << threads << " threads, grain " << grain;
            for (std::size_t i = 0; i < count; ++i)
                ASSERT_EQ(visits[i], 1) << "item " << i << ", " << threads << " threads, grain " << grain;
        }
}

TEST(WorkerPool, OneThreadRunsEverythingOnTheCallingThread) {
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<std::thread::id> ranOn(100);
    parallelFor(ranOn.size(), 1, [&](std::size_t i) { ranOn[i] = std::this_thread::get_id(); });
    for (const std::thread::id &id : ranOn) EXPECT_EQ(id, caller);
}

TEST(WorkerPool, NestedLoopsCompleteAndWriteTheirOwnOutputs) {
    const std::size_t outer = 16, inner = 200;
    std::vector<uint64_t> sums(outer, 0);
    parallelFor(outer, 0, [&](std::size_t o) {
        std::vector<uint64_t> values(inner, 0);
        parallelFor(inner, 0, [&](std::size_t i) { values[i] = o * 1000 + i; });
        sums[o] = std::accumulate(values.begin(), values.end(), uint64_t(0));
    });
    for (std::size_t o = 0; o < outer; ++o)
        EXPECT_EQ(sums[o], o * 1000 * inner + inner * (inner - 1) / 2) << "outer item " << o;
}

TEST(WorkerPool, LoopsFromSeveralThreadsAtOnceShareThePool) {
    // A background render and a BVH build (or two sessions) run loops at the same time.
    std::vector<std::vector<uint32_t>> results(4, std::vector<uint32_t>(5000, 0));
    std::vector<std::thread> callers;
    for (std::size_t t = 0; t < results.size(); ++t)
        callers.emplace_back([&, t] {
            for (int round = 0; round < 20; ++round)
                parallelForChunks(results[t].size(), 0, 64, [&](std::size_t begin, std::size_t end) {
                    for (std::size_t i = begin; i < end; ++i) results[t][i] += uint32_t(i + t);
                });
        });
    for (std::thread &caller : callers) caller.join();
    for (std::size_t t = 0; t < results.size(); ++t)
        for (std::size_t i = 0; i < results[t].size(); i += 997) EXPECT_EQ(results[t][i], 20u * uint32_t(i + t));
}

} // namespace
} // namespace mvcl
