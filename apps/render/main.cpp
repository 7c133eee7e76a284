// mvcl-render: the headless shell. Loads a scene, builds the tracer, renders, writes the image,
// prints what it did. All the work is in the framework; this file only wires it up.

#include "ProgressBar.h"
#include "RenderCommandLine.h"

#include <mvcl/core/Error.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/ImageIO.h>
#include <mvcl/view/Renderer.h>

#include <cstdio>
#include <exception>
#include <string>
#include <unistd.h>
#include <vector>

using namespace mvcl;
using namespace mvcl::cli;

namespace {

std::string sceneStem(const std::string &source) {
    if (source.rfind("builtin:", 0) == 0) return source.substr(8);
    return std::filesystem::path(source).stem().string();
}

const char *layerSourceName(LayerSource s) {
    switch (s) {
    case LayerSource::Unassigned: return "unassigned";
    case LayerSource::Builtin: return "built-in";
    case LayerSource::Extras: return "extras.layer";
    case LayerSource::Rule: return "rule";
    case LayerSource::Inferred: return "inferred";
    }
    return "?";
}

void printInfo(const Scene &scene) {
    const Bounds3f b = scene.bounds();
    const glm::dvec3 o = scene.worldOrigin;
    std::printf("scene      %s\n", scene.name.c_str());
    std::printf("triangles  %zu in %zu meshes; %zu spheres, %zu planes; %zu materials, %zu lights, %zu cameras\n",
                scene.triangleCount(), scene.meshes.size(), scene.spheres.size(), scene.planes.size(),
                scene.materials.size(), scene.lights.size(), scene.cameras.size());
    if (!b.isEmpty())
        std::printf("bounds     (%.6g, %.6g, %.6g) .. (%.6g, %.6g, %.6g)\n", o.x + b.min.x, o.y + b.min.y,
                    o.z + b.min.z, o.x + b.max.x, o.y + b.max.y, o.z + b.max.z);
    else
        std::printf("bounds     empty\n");
    for (const Layer &layer : scene.layers.layers()) {
        std::size_t meshes = 0, triangles = 0;
        for (const TriangleMesh &m : scene.meshes)
            if (m.layer == layer.id) ++meshes, triangles += m.indices.size();
        std::printf("layer %-4d %-20s %zu meshes, %zu triangles\n", layer.id, layer.name.c_str(), meshes, triangles);
    }
    for (const TriangleMesh &m : scene.meshes)
        std::printf("  mesh %-40s layer %d (%s), %zu triangles\n", m.name.c_str(), m.layer,
                    layerSourceName(m.layerSource), m.indices.size());
    if (scene.report.degenerateTrianglesDropped)
        std::printf("dropped    %zu degenerate triangles\n", scene.report.degenerateTrianglesDropped);
    if (scene.report.nonUnitNormalsFixed)
        std::printf("fixed      %zu non-unit normals\n", scene.report.nonUnitNormalsFixed);
    for (const std::string &w : scene.report.warnings) std::printf("warning    %s\n", w.c_str());
}

Camera chooseCamera(const Scene &scene, const RenderCommandLine &cl) {
    const float aspect = float(cl.width) / float(cl.height);
    const glm::vec3 origin(scene.worldOrigin);
    Camera camera;
    if (!cl.camera.empty()) {
        const CameraDesc *found = nullptr;
        for (std::size_t i = 0; i < scene.cameras.size(); ++i)
            if (scene.cameras[i].name == cl.camera || std::to_string(i) == cl.camera) found = &scene.cameras[i];
        if (!found)
            throw Error("command line", "--camera '" + cl.camera + "': the scene has " +
                                            std::to_string(scene.cameras.size()) + " cameras and none by that name or index");
        camera = Camera::fromDesc(*found);
    } else if (scene.name.rfind("builtin:", 0) == 0 && !scene.cameras.empty()) {
        camera = Camera::fromDesc(scene.cameras.front());
    } else {
        camera = Camera::framing(scene.bounds(), cl.fov.value_or(40.f), aspect);
    }
    // Explicit options override parts of the chosen view; they are in world space.
    const glm::vec3 eye = cl.eye ? *cl.eye - origin : camera.eye();
    const glm::vec3 target = cl.target ? *cl.target - origin : camera.target();
    return Camera::lookAt(eye, target, cl.up.value_or(camera.up()), cl.fov.value_or(camera.verticalFov()));
}

int run(const RenderCommandLine &cl) {
    SceneLoadOptions loadOptions;
    if (!cl.layerRules.empty()) {
        try {
            loadOptions.layerRules = LayerRules::fromString(cl.layerRules);
        } catch (const Error &e) { // a malformed option value is a usage error, not a bad file
            throw Error("command line", "--layer-rule: " + e.problem());
        }
    }
    if (!cl.layerRulesFile.empty()) {
        const LayerRules fileRules = LayerRules::fromJsonFile(cl.layerRulesFile);
        for (const LayerRule &rule : fileRules.rules()) loadOptions.layerRules.add(rule);
    }

    const Scene scene = loadScene(cl.source, loadOptions);
    if (cl.info) {
        printInfo(scene);
        return kExitOk;
    }

    const Tracer tracer(scene);
    const TracerBuildStats &build = tracer.buildStats();
    const Camera camera = chooseCamera(scene, cl);

    RenderSettings settings;
    settings.width = cl.width;
    settings.height = cl.height;
    settings.samplesPerPixel = cl.samplesPerPixel;
    settings.threads = cl.threads;
    settings.seed = cl.seed;
    const PolicyMap policies(cl.width, cl.height);
    Framebuffer image;
    ProgressBar bar(cl.progress && isatty(STDERR_FILENO));
    const RenderStats stats = Renderer(tracer).render(camera, policies, settings, image,
                                                      [&](float f) { bar.update(f); });
    bar.finish();

    const std::string output = cl.output.empty() ? "out/" + sceneStem(cl.source) + ".png" : cl.output;
    try {
        writeImage(output, image);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return kExitOutput;
    }

    std::printf("scene      %s\n", scene.name.c_str());
    std::printf("geometry   %zu triangles in %zu meshes, %zu spheres, %zu planes, %d layers, %zu lights\n",
                build.triangles, scene.meshes.size(), scene.spheres.size(), scene.planes.size(),
                scene.layers.count(), scene.lights.size());
    std::printf("bvh        %.1f ms build, %zu nodes, depth %d, %.1f MiB\n", build.buildMilliseconds, build.nodes,
                build.maxDepth, double(build.memoryBytes) / (1024.0 * 1024.0));
    std::printf("render     %dx%d, %d spp, %d threads: %.1f ms\n", cl.width, cl.height, cl.samplesPerPixel,
                stats.threads, stats.renderMilliseconds);
    std::printf("rays       %.3f M (primary %.3f M, shadow %.3f M, reflection %.3f M, refraction %.3f M), %.2f Mrays/s\n",
                double(stats.rays.total()) * 1e-6, double(stats.rays.primary) * 1e-6, double(stats.rays.shadow) * 1e-6,
                double(stats.rays.reflection) * 1e-6, double(stats.rays.refraction) * 1e-6,
                stats.raysPerSecond() * 1e-6);
    std::printf("wrote      %s\n", output.c_str());
    return kExitOk;
}

} // namespace

int main(int argc, char **argv) {
    RenderCommandLine cl;
    try {
        cl = parseRenderCommandLine(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return kExitUsage;
    }
    if (cl.help) {
        std::fputs(renderUsage().c_str(), stdout);
        return kExitOk;
    }
    if (cl.version) {
        std::printf("mvcl-render 0.1.0\n");
        return kExitOk;
    }
    try {
        return run(cl);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return e.source() == "command line" ? kExitUsage : kExitBadInput;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-render: internal error: %s\n", e.what());
        return kExitInternal;
    }
}
