#pragma once
/// \file BenchSupport.h
/// What mvcl-bench's measurements share: wall-clock timing, rays on the worker pool, the
/// meshes both tracers get.

#include <mvcl/core/WorkerPool.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/GltfLoader.h>
#include <mvcl/model/Scene.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <fstream>
#include <string>

namespace mvcl::bench {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Runs f(i) for i in [0, n) on `threads` threads of the framework's worker pool, in chunks of
/// up to 256 rays: one ray per item would cost more in scheduling than a fast ray takes.
template <class F>
void parallelRays(int n, int threads, const F &f) {
    parallelForChunks(std::size_t(n), threads, 256, [&f](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) f(int(i));
    });
}

/// Best (shortest) wall time of `repeat` runs of f.
template <class F>
double bestSeconds(int repeat, const F &f) {
    double best = 1e300;
    for (int r = 0; r < repeat; ++r) {
        const auto start = Clock::now();
        f();
        best = std::min(best, secondsSince(start));
    }
    return best;
}

/// The CPU's model name as the system reports it ("model name" in /proc/cpuinfo, what lscpu
/// prints), so that every ratio is printed beside the CPU it was measured on; "unknown CPU"
/// where the system does not say.
inline std::string cpuModelName() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) != 0) continue;
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) break;
        const std::size_t start = line.find_first_not_of(" \t", colon + 1);
        return start == std::string::npos ? std::string("unknown CPU") : line.substr(start);
    }
    return "unknown CPU";
}

/// Only the triangle meshes of `scene`: both tracers get exactly the same geometry.
inline Scene meshesOf(Scene scene) {
    scene.spheres.clear();
    scene.planes.clear();
    return scene;
}

/// The triangle meshes of `source` (a model file or builtin:NAME) as the file has them.
inline Scene loadMeshes(const std::string &source) {
    return meshesOf(source.rfind("builtin:", 0) == 0 ? makeBuiltinScene(source.substr(8)) : loadGltf(source));
}

} // namespace mvcl::bench
