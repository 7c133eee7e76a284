#include <mvcl/core/WorkerPool.h>

#include "WorkerArena_p.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

namespace mvcl {

int workerThreadCount() {
    static const int count = int(std::max(1u, std::thread::hardware_concurrency()));
    return count;
}

namespace detail {

tbb::task_arena &workerArena(int threads) {
    // More threads than cores would only oversubscribe them (and TBB caps its workers there).
    const int concurrency = threads > 0 ? std::min(threads, workerThreadCount()) : workerThreadCount();
    static std::mutex mutex;
    static std::map<int, std::unique_ptr<tbb::task_arena>> arenas;
    std::lock_guard lock(mutex);
    std::unique_ptr<tbb::task_arena> &arena = arenas[concurrency];
    if (!arena) arena = std::make_unique<tbb::task_arena>(concurrency);
    return *arena;
}

} // namespace detail

void runParallelChunks(std::size_t count, int threads, std::size_t grain, ChunkFunction function,
                       void *context) {
    if (count == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    if (threads == 1 || count <= grain) {
        for (std::size_t begin = 0; begin < count; begin += grain)
            function(context, begin, std::min(count, begin + grain));
        return;
    }
    // simple_partitioner: chunks of at most `grain` items, split the same way whatever the
    // thread count, so callers control the granularity (a tile, a row band).
    detail::workerArena(threads).execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, count, grain),
            [&](const tbb::blocked_range<std::size_t> &r) { function(context, r.begin(), r.end()); },
            tbb::simple_partitioner());
    });
}

} // namespace mvcl
