#include "LoadBench.h"

#include "CommandLineValues.h"

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>

#include <CLI/CLI.hpp>

#include <tiny_obj_loader.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <time.h>
#include <vector>

namespace mvcl::bench {

namespace {

/// A UV sphere of about `triangles` triangles: closed, every vertex shared, like a scanned organ.
void generate(std::size_t triangles, const std::filesystem::path &dir) {
    const auto rings = std::size_t(std::max(4.0, std::sqrt(double(triangles) / 2.0)));
    const std::size_t segments = std::max<std::size_t>(3, triangles / (2 * rings));
    std::vector<glm::vec3> positions{{0.f, 1.f, 0.f}};
    for (std::size_t r = 1; r < rings; ++r) {
        const double theta = 3.14159265358979 * double(r) / double(rings);
        for (std::size_t s = 0; s < segments; ++s) {
            const double phi = 2.0 * 3.14159265358979 * double(s) / double(segments);
            positions.emplace_back(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                                   float(std::sin(theta) * std::sin(phi)));
        }
    }
    positions.emplace_back(0.f, -1.f, 0.f);
    const auto ring = [&](std::size_t r, std::size_t s) { return std::uint32_t(1 + (r - 1) * segments + s % segments); };
    std::vector<glm::uvec3> faces;
    for (std::size_t s = 0; s < segments; ++s) faces.emplace_back(0, ring(1, s + 1), ring(1, s));
    for (std::size_t r = 1; r + 1 < rings; ++r)
        for (std::size_t s = 0; s < segments; ++s) {
            faces.emplace_back(ring(r, s), ring(r, s + 1), ring(r + 1, s));
            faces.emplace_back(ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s));
        }
    const auto south = std::uint32_t(positions.size() - 1);
    for (std::size_t s = 0; s < segments; ++s) faces.emplace_back(south, ring(rings - 1, s), ring(rings - 1, s + 1));

    std::filesystem::create_directories(dir);
    std::ofstream stl(dir / "sphere.stl", std::ios::binary);
    stl << std::string(80, ' ');
    const auto count = std::uint32_t(faces.size());
    stl.write(reinterpret_cast<const char *>(&count), 4);
    for (const glm::uvec3 &f : faces) {
        const glm::vec3 n = glm::normalize(glm::cross(positions[f.y] - positions[f.x], positions[f.z] - positions[f.x]));
        stl.write(reinterpret_cast<const char *>(&n), 12);
        for (int k = 0; k < 3; ++k) stl.write(reinterpret_cast<const char *>(&positions[f[k]]), 12);
        stl.write("\0\0", 2);
    }
    std::ofstream ply(dir / "sphere.ply", std::ios::binary);
    ply << "ply\nformat binary_little_endian 1.0\nelement vertex " << positions.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << faces.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    ply.write(reinterpret_cast<const char *>(positions.data()), std::streamsize(positions.size() * sizeof(glm::vec3)));
    for (const glm::uvec3 &f : faces) {
        ply.put(3);
        ply.write(reinterpret_cast<const char *>(&f), 12);
    }
    std::ofstream obj(dir / "sphere.obj");
    obj.precision(9);
    for (const glm::vec3 &p : positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    obj << "g sphere\n";
    for (const glm::uvec3 &f : faces) obj << "f " << f.x + 1 << ' ' << f.y + 1 << ' ' << f.z + 1 << '\n';
    std::printf("wrote      %zu triangles, %zu vertices to %s/sphere.{stl,ply,obj}\n", faces.size(), positions.size(),
                dir.string().c_str());
}

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

std::optional<MeshFormat> meshFormatOf(const std::filesystem::path &file) {
    const std::string ext = file.extension().string();
    if (ext == ".obj") return MeshFormat::Obj;
    if (ext == ".stl") return MeshFormat::Stl;
    if (ext == ".ply") return MeshFormat::Ply;
    return std::nullopt;
}

std::size_t triangleCount(const Scene &scene) { return scene.triangleCount(); }
std::size_t triangleCount(std::size_t triangles) { return triangles; }

} // namespace

int runLoadBench(int argc, char **argv) {
    CLI::App app("mvcl-bench load: how fast model files are read; the best of --repeat loads of each file.",
                 "mvcl-bench load");
    std::vector<std::string> files;
    int repeat = 5;
    std::size_t generateTriangles = 0;
    std::string generateDir;
    app.add_option("files", files, "model files (any format loadScene reads)");
    app.add_option("--repeat", repeat, "loads per file (default 5); the fastest is reported")->check(CLI::Range(1, 1000));
    app.add_option("--generate", generateTriangles, "write a closed mesh of about N triangles (see --to) and exit");
    app.add_option("--to", generateDir, "folder for --generate (default out/load-bench)");
    try {
        if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
            std::fputs(app.help().c_str(), stdout);
            return 0;
        }
        if (generateTriangles > 0) {
            generate(generateTriangles, generateDir.empty() ? "out/load-bench" : generateDir);
            return 0;
        }
        if (files.empty()) throw Error("command line", "no file given (see mvcl-bench load --help)");
        for (const std::string &file : files) {
            const double megabytes = double(std::filesystem::file_size(file)) / 1e6;
            // Wall time and the process's CPU time: on a shared machine the wall clock also counts
            // the time other processes held the core (the readers run on one thread; loadScene's
            // layer inference may use more).
            const auto report = [&](const char *what, const auto &load) {
                double best = HUGE_VAL, bestCpu = HUGE_VAL;
                std::size_t triangles = 0;
                for (int i = 0; i < repeat; ++i) {
                    const double cpuStart = processCpuSeconds();
                    const auto start = std::chrono::steady_clock::now();
                    triangles = triangleCount(load());
                    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
                    bestCpu = std::min(bestCpu, processCpuSeconds() - cpuStart);
                }
                std::printf("%-10s %-32s %6.1f MB %8zu triangles  wall %7.1f ms %6.1f MB/s  cpu %7.1f ms %6.1f MB/s\n",
                            what, file.c_str(), megabytes, triangles, best * 1e3, megabytes / best, bestCpu * 1e3,
                            megabytes / bestCpu);
            };
            // OBJ: tinyobjloader's own parse first, as its example program calls it (from the file
            // name, triangulating), the yardstick for mvcl's OBJ reader that parses with it.
            if (meshFormatOf(file) == MeshFormat::Obj)
                report("tinyobj", [&] {
                    tinyobj::attrib_t attrib;
                    std::vector<tinyobj::shape_t> shapes;
                    std::vector<tinyobj::material_t> materials;
                    std::string warn, err;
                    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, file.c_str()))
                        throw Error(file, "tinyobjloader: " + err);
                    std::size_t corners = 0;
                    for (const tinyobj::shape_t &shape : shapes) corners += shape.mesh.indices.size();
                    return corners / 3;
                });
            // The reader alone (parsing, checks, welding, re-centring, closure), then everything
            // loadScene adds (layer inference, names, lights).
            if (const std::optional<MeshFormat> format = meshFormatOf(file))
                report("read", [&] { return loadMeshFile(file, *format); });
            SceneLoadOptions options;
            options.defaultLights = DefaultLights::Never;
            report("loadScene", [&] { return loadScene(file, options); });
        }
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench load: %s\n", e.what());
        return e.source() == "command line" ? 2 : 1;
    }
    return 0;
}

} // namespace mvcl::bench
