#pragma once
/// \file WorkerPool.h
/// The framework's one worker pool. Every parallel loop in mvcl (the renderer's tiles, the BVH
/// build, layer inference, policy composition, the benches) runs on it, so a render and a build
/// that overlap share the cores instead of oversubscribing them. oneTBB's scheduler is
/// underneath; nothing of it shows in this header.

#include <mvcl/core/Export.h>

#include <cstddef>
#include <type_traits>

namespace mvcl {

/// Threads a loop asked for 0 threads uses: the machine's cores (at least 1).
MVCL_EXPORT int workerThreadCount();

/// The type-erased loop under parallelForChunks(): public because the template calls it, not
/// meant to be called directly.
using ChunkFunction = void (*)(void *context, std::size_t begin, std::size_t end);
MVCL_EXPORT void runParallelChunks(std::size_t count, int threads, std::size_t grain, ChunkFunction function,
                       void *context);

/// Calls body(begin, end) for chunks of [0, count) of at most `grain` items (≥ 1), on at most
/// `threads` threads (0 = all cores; the calling thread works too) and returns when all are
/// done. Chunks run in any order and concurrently: each must write only its own output, and
/// then the result does not depend on the thread count. Safe to call from inside a body
/// (nested loops share the same threads).
template <class Body>
void parallelForChunks(std::size_t count, int threads, std::size_t grain, Body &&body) {
    using B = std::remove_reference_t<Body>;
    runParallelChunks(
        count, threads, grain,
        [](void *context, std::size_t begin, std::size_t end) { (*static_cast<B *>(context))(begin, end); },
        const_cast<void *>(static_cast<const void *>(&body)));
}

/// Calls body(i) for every i in [0, count), items handed out one at a time: make items coarse
/// (tiles, subtrees, chunks of thousands).
template <class Body>
void parallelFor(std::size_t count, int threads, Body &&body) {
    parallelForChunks(count, threads, 1, [&body](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) body(i);
    });
}

} // namespace mvcl
