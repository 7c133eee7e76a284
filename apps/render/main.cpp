// mvcl-render: the headless shell. Loads a scene, builds the tracer, renders, writes the image,
// prints what it did. All the work is in the framework; this file only wires it up.

#include "AnimationCommand.h"
#include "ProgressBar.h"
#include "ViewsCommand.h"
#include "RenderCommandLine.h"

#include <mvcl/controller/ViewSetup.h>
#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/io/AnimationFile.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/LoadedScene.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/tracer/LayerContactProbe.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/ConvergenceLog.h>
#include <mvcl/view/ImageIO.h>
#include <mvcl/view/LensOutlines.h>
#include <mvcl/view/RenderSession.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
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
    case LayerSource::File: return "file";
    }
    return "?";
}

/// What the loader assumed for files that do not say, and the options that change it.
void printAssumptions(const Scene &scene) {
    if (scene.report.assumptions.empty()) return;
    std::string text;
    for (const std::string &a : scene.report.assumptions) text += (text.empty() ? "" : ", ") + a;
    std::printf("assumed    %s (the file does not say; --up y|z, --unit mm|cm|m|in)\n", text.c_str());
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
    const auto closureName = [](MeshClosure closure) {
        return closure == MeshClosure::Open ? "open" : closure == MeshClosure::Outward ? "closed" : "closed, inward";
    };
    for (const TriangleMesh &m : scene.meshes)
        if (m.layerSource == LayerSource::Inferred)
            std::printf("  mesh %-40s layer %d (inferred, confidence %.2f), %zu triangles, %s\n", m.name.c_str(),
                        m.layer, double(m.layerConfidence), m.indices.size(), closureName(m.closure));
        else
            std::printf("  mesh %-40s layer %d (%s), %zu triangles, %s\n", m.name.c_str(), m.layer,
                        layerSourceName(m.layerSource), m.indices.size(), closureName(m.closure));
    if (scene.report.degenerateTrianglesDropped)
        std::printf("dropped    %zu degenerate triangles\n", scene.report.degenerateTrianglesDropped);
    if (scene.report.nonUnitNormalsFixed)
        std::printf("fixed      %zu non-unit normals\n", scene.report.nonUnitNormalsFixed);
    for (const std::string &w : scene.report.warnings) std::printf("warning    %s\n", w.c_str());
    printAssumptions(scene);
}

/// 31420 → "31,420".
std::string grouped(uint64_t number) {
    const std::string digits = std::to_string(number);
    std::string text;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) text.push_back(',');
        text.push_back(digits[i]);
    }
    return text;
}

/// Characters on screen, not bytes: ranges say "∞".
std::size_t displayWidth(const std::string &text) {
    return std::size_t(std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

/// Every lens type with its property table, generated from the declarations.
/// Markdown cells: a '|' would end the cell.
std::string markdownCell(const std::string &text) {
    std::string cell;
    for (const char c : text) {
        if (c == '|') cell += '\\';
        cell += c;
    }
    return cell;
}

/// The property tables of docs/lenses.md, one section per lens type (no module paths: they
/// differ between machines, and the docs must not).
/// The doc sentence, with the condition under which the property is used.
std::string docWithCondition(const PropertyDecl &decl) {
    if (decl.usedWhen.property.empty()) return decl.doc;
    return decl.doc + " (used when " + decl.usedWhen.property + "=" + decl.usedWhen.value + ")";
}

void printLensTypesMarkdown(const LensRegistry &registry) {
    for (const std::string &type : registry.lensTypes()) {
        const std::shared_ptr<Lens> lens = registry.create(type);
        std::printf("#### %s\n\n%s\n\n| name | type | default | range | meaning |\n|---|---|---|---|---|\n", type.c_str(),
                    lens->info().description.c_str());
        for (const PropertyDecl &decl : lens->properties())
            std::printf("| `%s` | %s | `%s` | %s | %s |\n", decl.name.c_str(), propertyTypeName(decl.type),
                        markdownCell(decl.defaultValue.toString()).c_str(), markdownCell(decl.rangeText()).c_str(),
                        markdownCell(docWithCondition(decl)).c_str());
        std::printf("\n");
    }
}

void printLensTypes(const LensRegistry &registry) {
    for (const std::string &type : registry.lensTypes()) {
        const std::shared_ptr<Lens> lens = registry.create(type);
        std::printf("%s: %s\n    from %s\n", type.c_str(), lens->info().description.c_str(),
                    registry.origin(type).c_str());
        std::vector<std::vector<std::string>> rows{{"property", "type", "default", "range", "doc"}};
        for (const PropertyDecl &decl : lens->properties())
            rows.push_back({decl.name, propertyTypeName(decl.type), decl.defaultValue.toString(), decl.rangeText(),
                            docWithCondition(decl)});
        std::vector<std::size_t> widths(rows.front().size(), 0);
        for (const auto &row : rows)
            for (std::size_t column = 0; column < row.size(); ++column)
                widths[column] = std::max(widths[column], displayWidth(row[column]));
        for (const auto &row : rows) {
            std::string line = "   ";
            for (std::size_t column = 0; column + 1 < row.size(); ++column)
                line.append(" ").append(row[column]).append(widths[column] - displayWidth(row[column]) + 1, ' ');
            std::printf("%s %s\n", line.c_str(), row.back().c_str());
        }
    }
}

/// The command line as a view request: what ViewSetup chooses the scene, camera, lenses and
/// layer rules from, as the viewer does.
ViewRequest viewRequest(const RenderCommandLine &cl) {
    ViewRequest request;
    request.source = cl.source;
    request.moreSources = cl.moreSources;
    request.sessionFile = cl.lensFile;
    request.sessionView = sessionViewOf(cl);
    request.lensSpecs = cl.lensSpecs;
    request.sceneCamera = cl.camera;
    request.eye = cl.eye;
    request.target = cl.target;
    request.up = cl.up;
    request.verticalFovDegrees = cl.fov;
    // Inline rules first, then the rules file: the first matching rule wins.
    if (!cl.layerRules.empty()) {
        try {
            request.loadOptions.layerRules = LayerRules::fromString(cl.layerRules);
        } catch (const Error &e) { // a malformed option value is a usage error, not a bad file
            throw Error("command line", "--layer-rule: " + e.problem());
        }
    }
    if (!cl.layerRulesFile.empty()) {
        const LayerRules fileRules = LayerRules::fromJsonFile(cl.layerRulesFile);
        for (const LayerRule &rule : fileRules.rules()) request.loadOptions.layerRules.add(rule);
    }
    if (!cl.modelUp.empty()) request.loadOptions.upAxis = upAxisFromName(cl.modelUp);
    if (!cl.unit.empty()) request.loadOptions.unit = lengthUnitFromName(cl.unit);
    request.loadOptions.defaultLights = cl.defaultLights ? DefaultLights::WhenTheFileHasNone : DefaultLights::Never;
    request.loadOptions.memoryBudgetBytes = cl.memoryBudgetMiB << 20;
    if (!cl.layerContact.empty()) {
        try {
            request.loadOptions.layerContact = LayerContact::parse(cl.layerContact);
        } catch (const Error &e) { // a usage error, like a bad --layer-rule
            throw Error("command line", "--layer-contact: " + e.problem());
        }
    }
    return request;
}

/// Near-coincident layers and the contact tolerance that would make them render clean.
void printLayerContacts(const Scene &scene) {
    std::printf("contact    %s\n", scene.layerContact.isEnabled()
                                        ? ("--layer-contact " + scene.layerContact.toString()).c_str()
                                        : "off");
    if (scene.layers.layers().size() < 2) return;
    const Tracer tracer(scene);
    const LayerContactReport report = probeLayerContacts(tracer);
    for (const NearCoincidentLayers &p : report.pairs)
        std::printf("           layers %d and %d nearly touch: %zu of %zu sampled facets within %.3g units\n",
                    p.outerLayer, p.innerLayer, p.samples, p.sampled, p.maxSeparation);
    if (report.suggested.isEnabled())
        std::printf("           suggested: --layer-contact %s (or \"layerContact\": {\"relative\": %s} in a session file)\n",
                    report.suggested.toString().c_str(), report.suggested.toString().c_str());
    else if (!report.pairs.empty())
        std::printf("           they coincide up to float rounding: no tolerance needed\n");
}

void printLensCosts(const LensStack &stack, const PolicyMap &policies, const RenderPassStats &stats) {
    for (const LensCost &cost : stack.costs(policies, stats.perPolicy)) {
        const Lens &lens = *stack.lens(cost.index);
        std::printf("lens %d %s '%s': %s px, %s rays, %.1f ms%s\n", cost.index, lens.typeName().c_str(),
                    cost.label.c_str(), grouped(cost.pixels).c_str(), grouped(cost.rays).c_str(), cost.milliseconds,
                    lens.snapshot()->enabled ? "" : " (disabled)");
    }
    std::printf("policies   %zu distinct (base included), %s px blend several (feathered edges)\n",
                policies.policies().size(), grouped(policies.blendedPixelCount()).c_str());
}

std::string samplingName(const RenderSettings &s) {
    char text[160];
    switch (s.sampling) {
    case SamplingMode::Fixed: std::snprintf(text, sizeof text, "%d spp", s.samplesPerPixel); break;
    case SamplingMode::Progressive:
    case SamplingMode::Adaptive:
        char limit[32];
        if (s.timeLimitSeconds > 0) std::snprintf(limit, sizeof limit, "%g s", s.timeLimitSeconds);
        else std::snprintf(limit, sizeof limit, "none");
        std::snprintf(text, sizeof text, "%s %d..%d spp, target error %g, time limit %s",
                      s.sampling == SamplingMode::Adaptive ? "adaptive" : "progressive",
                      s.sampling == SamplingMode::Adaptive ? s.minSamplesPerPixel : 1, s.maxSamplesPerPixel,
                      double(s.targetError), limit);
        break;
    }
    return text;
}

/// What the integrator left out, and the rays that saved against forcing every stage.
void printSkippedStages(const RayCounters &rays, const RenderSettings &settings) {
    if (!settings.skipUnneededStages) {
        std::printf("skipped    nothing: every stage forced (--force-all-stages)\n");
        return;
    }
    const uint64_t forced = rays.total() + rays.skippedShadowRays;
    std::printf("skipped    %.3f M shadow rays (lights nothing can block), %.3f M transparent walks (any-hit instead), "
                "%.3f M secondary checks, %.3f M identity colour maps: %.3f M rays saved (%.1f %% of %.3f M)\n",
                double(rays.skippedShadowRays) * 1e-6, double(rays.skippedTransparentWalks) * 1e-6,
                double(rays.skippedSecondaryChecks) * 1e-6, double(rays.skippedColorMaps) * 1e-6,
                double(rays.skippedShadowRays) * 1e-6,
                forced > 0 ? 100.0 * double(rays.skippedShadowRays) / double(forced) : 0.0, double(forced) * 1e-6);
}

int run(const RenderCommandLine &cl) {
    LensRegistry registry;
    for (const Error &skipped : registry.loadModules(LensRegistry::defaultSearchPath()))
        std::fprintf(stderr, "mvcl-render: warning: plugin skipped: %s\n", skipped.what());
    if (cl.listLenses) {
        if (cl.listFormat == "markdown")
            printLensTypesMarkdown(registry);
        else
            printLensTypes(registry);
        return kExitOk;
    }
    const ViewRequest request = viewRequest(cl);
    if (cl.view == "all") return renderAllViews(cl, registry, request);
    const ViewSetup setup = ViewSetup::prepare(request, registry);
    // A view of a session of several may compare two stacks.
    const std::optional<CompareDescription> compare =
        setup.sessionFile ? setup.sessionFile->views[std::size_t(request.sessionView)].compare : std::nullopt;
    const LensStack &lenses = setup.session.lenses;
    // Read before the scene loads: a bad animation file fails at once, not after the BVH build.
    const std::optional<Animation> animation =
        isAnimation(cl) ? std::optional<Animation>(commandLineAnimation(cl, lenses)) : std::nullopt;

    if (cl.info) {
        Scene scene = loadScene(setup.sources(), setup.loadOptions);
        setup.renameLayers(scene);
        printInfo(scene);
        printLayerContacts(scene);
        return kExitOk;
    }
    // One BVH for layer inference and rendering.
    const LoadedScene loaded = LoadedScene::load(setup.sources(), setup.loadOptions);
    setup.renameLayers(*loaded.scene);
    const Scene &scene = *loaded.scene;
    const Tracer &tracer = *loaded.tracer;
    const TracerBuildStats &build = tracer.buildStats();
    const Camera camera = setup.camera(scene, request, float(cl.width) / float(cl.height));
    try {
        if (!cl.saveLensesFile.empty()) writeLensStackFile(cl.saveLensesFile, setup.describe(scene, camera));
        if (animation && !cl.saveAnimationFile.empty()) {
            writeAnimationFile(cl.saveAnimationFile, *animation, lenses);
            std::printf("saved      %s (the animation)\n", cl.saveAnimationFile.c_str());
        }
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return kExitOutput;
    }

    RenderSession session(tracer);
    session.setSettings(renderSettings(cl));
    session.setCamera(camera);
    RayPolicy base;
    base.query(RayType::Primary).layerMask = setup.session.visibleLayers;
    session.setBasePolicy(base);
    setViewStacks(session, lenses, compare);
    if (animation)
        return renderAnimation(cl, *animation, session, lenses, camera, scene,
                               cl.output.empty() ? "out/" + sceneStem(setup.source) + "/%04d.png" : cl.output);
    // Too many overlapping clip volumes would render a wrong cut; say so instead of rendering.
    LensContext lensContext = LensContext::forScene(scene);
    lensContext.camera = {"", camera.eye(), camera.target(), camera.up(), camera.verticalFovDegrees()};
    lensContext.imageWidth = cl.width;
    lensContext.imageHeight = cl.height;
    LensStack::checkClipVolumes(lenses.compose(lensContext, base));
    std::unique_ptr<ConvergenceLog> log;
    try {
        if (!cl.convergenceLogFile.empty()) log = std::make_unique<ConvergenceLog>(cl.convergenceLogFile);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return kExitOutput;
    }
    ProgressBar bar(cl.progress && isatty(STDERR_FILENO));
    session.setProgressCallback([&](float f) { bar.update(f); });
    const RenderPassStats stats = session.renderUntilIdle([&](const RenderPassStats &pass) {
        if (log) log->addPass(pass, session.convergence());
    });
    // A faulty plugin costs its own lens only: it renders as disabled, and the user is told why
    // (after the render, so that faults in the session's context are included).
    for (const std::shared_ptr<Lens> &lens : lenses.lenses())
        if (const std::string fault = lens->fault(); !fault.empty())
            std::fprintf(stderr, "mvcl-render: warning: %s; the lens is disabled\n", fault.c_str());
    bar.finish();
    Framebuffer image = session.image();
    drawViewOutlines(lenses, compare, image);

    const std::string output = cl.output.empty() ? "out/" + sceneStem(setup.source) + ".png" : cl.output;
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
    std::string layerNames;
    for (const Layer &layer : scene.layers.layers())
        layerNames += (layerNames.empty() ? "" : ", ") + std::to_string(layer.id) + " " + layer.name;
    std::printf("layers     %s\n", layerNames.c_str());
    printAssumptions(scene);
    std::printf("load       %.1f ms: %.1f ms reading and checking, %.1f ms layer inference\n",
                loaded.readMilliseconds + scene.report.inferenceMilliseconds, loaded.readMilliseconds,
                scene.report.inferenceMilliseconds);
    // Traversal walks the wide tree; the depth is the binary tree's it was collapsed from (a few
    // primitives give one wide node over a binary tree several levels deep), so both are named.
    std::printf("bvh        %.1f ms build, %zu wide node%s over %zu leaves (binary tree depth %d), %.1f MiB\n",
                build.buildMilliseconds, build.nodes, build.nodes == 1 ? "" : "s", build.leaves, build.maxDepth,
                double(build.memoryBytes) / (1024.0 * 1024.0));
    const RenderSettings settings = session.settings();
    const ConvergenceStats reached = session.convergence();
    std::printf("render     %dx%d, %s, %d threads: %.1f ms\n", cl.width, cl.height, samplingName(settings).c_str(),
                settings.threads > 0 ? std::min(settings.threads, workerThreadCount()) : workerThreadCount(),
                stats.milliseconds);
    std::printf("samples    %d min, %.2f mean, %d max per pixel; estimated error %.4f mean, %.4f max",
                reached.minSamples, reached.meanSamples, reached.maxSamples, reached.meanError, reached.maxError);
    if (reached.estimatedRelativeMse) std::printf("; estimated relMSE %.3g", *reached.estimatedRelativeMse);
    std::printf("\n");
    std::printf("rays       %.3f M (primary %.3f M, shadow %.3f M, reflection %.3f M, refraction %.3f M), %.2f Mrays/s\n",
                double(stats.rays.total()) * 1e-6, double(stats.rays.primary) * 1e-6, double(stats.rays.shadow) * 1e-6,
                double(stats.rays.reflection) * 1e-6, double(stats.rays.refraction) * 1e-6,
                stats.milliseconds > 0 ? double(stats.rays.total()) / (stats.milliseconds * 1e3) : 0.0);
    printSkippedStages(stats.rays, settings);
    if (!lenses.isEmpty()) printLensCosts(lenses, session.policyMap(), stats);
    if (!cl.saveLensesFile.empty()) std::printf("saved      %s\n", cl.saveLensesFile.c_str());
    if (log) std::printf("logged     %s (%d passes)\n", cl.convergenceLogFile.c_str(), log->passCount());
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
