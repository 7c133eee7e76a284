#pragma once
// Private: the task arena behind the worker pool, for framework code that needs more than a
// loop (the BVH build pushes subtree tasks with tbb::task_group inside workerArena().execute).

#include <tbb/task_arena.h>

namespace mvcl::detail {

/// The arena that runs work on at most `threads` threads (0 = all cores). Arenas are created
/// once per thread count and live as long as the process; all of them share TBB's one pool
/// of worker threads.
tbb::task_arena &workerArena(int threads);

} // namespace mvcl::detail
