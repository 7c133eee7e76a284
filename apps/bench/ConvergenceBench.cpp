// mvcl-bench convergence: how fast the error of an image falls with wall time under the three
// ways a RenderSession spends samples.
//
//   mvcl-bench convergence [model | builtin:NAME] [--lenses FILE] [--size WxH] [--seeds N]
//                          [--csv FILE] [--max-spp N] [--reference-spp N] [--threads N]
//                          [--adaptive-error E] [--adaptive-min N] [--adaptive-max-spp N]
//                          [--cache DIR] [--no-flip]
//
// 1. A reference: two Fixed renders at --reference-spp with seeds no measurement uses, averaged.
//    Half their RMS difference estimates the reference's own RMSE (each is off by σ, their
//    difference by √2·σ, their mean by σ/√2). Cached on disk, keyed by everything it depends on.
// 2. For each seed: uniform = Fixed renders at 1, 2, 4, … max-spp samples, each its own session;
//    progressive = one Progressive session up to max-spp, measured after every pass;
//    adaptive = one Adaptive session (targetError --adaptive-error, default 1e-5; 0 would turn
//    the error test off) up to --adaptive-max-spp (default 8 × max-spp: spending more samples
//    where the error is is what adaptive sampling is for), measured after every pass, stopped
//    once its relMSE is below half of the same seed's uniform final relMSE.
//    One RenderSession class does all three, so they share the sampler and the renderer.
// 3. Time = wall clock of renderPass() calls only (never the error computation).
//    Errors against the reference: RMSE, relMSE (ε = 0.01), PSNR (peak 1, clamped), LDR-FLIP.
//
// Output: a CSV (one row per measurement), a table of means over seeds, and the line
// "adaptive reaches uniform's final error in R× the time" (uniform's final error: its relMSE at
// max-spp, mean over seeds; adaptive's time: interpolated log-log on its mean curve).

#include "ConvergenceBench.h"

#include "CommandLineValues.h"
#include "ConvergenceCurves.h"
#include "FlipError.h"
#include "ImageError.h"

#include <mvcl/core/Error.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/ImageIO.h>
#include <mvcl/view/RenderSession.h>

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mvcl::bench {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Seeds of the two reference renders: far from the measurement seeds 1 … N, so no measured
// render shares a sample with the reference it is compared to.
constexpr uint32_t kReferenceSeeds[2] = {0x5eed0001u, 0x5eed0002u};
constexpr const char *kDefaultLensFile = "assets/lenses/cube-in-cube.json";

struct Options {
    std::string model;
    std::string lensFile;
    int width = 320;
    int height = 240;
    int seeds = 3;
    std::string csv; // default out/convergence-<scene>.csv
    int maxSpp = 256;
    int referenceSpp = 4096;
    int threads = 0;
    /// Small, not 0: a target of 0 switches the error test off (RenderSettings), which makes
    /// Adaptive sample exactly like Progressive.
    float adaptiveError = 1e-5f;
    int adaptiveMin = RenderSettings{}.minSamplesPerPixel;
    int adaptiveMaxSpp = 0; ///< 0: 8 × maxSpp
    std::string cacheDir = "out/convergence-cache";
    bool flip = true;
};

const char *kUsage =
    "usage: mvcl-bench convergence [model | builtin:NAME] [--lenses FILE] [--size WxH] [--seeds N]\n"
    "                              [--csv FILE] [--max-spp N] [--reference-spp N] [--threads N]\n"
    "                              [--adaptive-error E] [--adaptive-min N] [--adaptive-max-spp N]\n"
    "                              [--cache DIR] [--no-flip]";

/// The options, or nothing when --help was asked for (the help is printed).
std::optional<Options> parseOptions(int argc, char **argv) {
    Options o;
    CLI::App app("mvcl-bench convergence: error against run time of uniform, progressive and adaptive sampling.",
                 "mvcl-bench convergence");
    app.formatter(std::make_shared<cli::UsageFormatter>(kUsage));
    app.set_help_flag("-h,--help", "this text");
    app.add_option("model", o.model,
                   "model file or builtin:NAME (default: builtin:cube-in-cube under "
                   "assets/lenses/cube-in-cube.json)")
        ->option_text(" ");
    app.add_option("--lenses", o.lensFile, "lens-stack file: lenses, camera, layer rules and (without a model) scene")
        ->type_name("FILE");
    cli::addImageSizeOption(app, o.width, o.height, "image size (default 320x240)");
    app.add_option("--seeds", o.seeds, "runs of each method, seeds 1..N (default 3)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(1, 1000));
    app.add_option("--csv", o.csv, "where the measurements go (default out/convergence-<scene>.csv)")->type_name("FILE");
    app.add_option("--max-spp", o.maxSpp, "uniform's largest spp and the others' cap (default 256)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(1, 1 << 16));
    app.add_option("--reference-spp", o.referenceSpp, "samples per pixel of each reference render (default 4096)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(1, 1 << 20));
    app.add_option("--threads", o.threads, "0 = all cores (default 0)")->type_name("N")->check(cli::wholeNumberIn(0, 1024));
    app.add_option("--adaptive-error", o.adaptiveError, "Adaptive's target error, > 0 (default 1e-5)")
        ->type_name("E")
        ->check(cli::numberBetween(0.0, 1e30, "greater than 0"));
    app.add_option("--adaptive-min", o.adaptiveMin, "Adaptive's samples before its estimate counts (default 8)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(2, 1 << 16));
    app.add_option("--adaptive-max-spp", o.adaptiveMaxSpp, "Adaptive's most samples per pixel (default 8 × --max-spp)")
        ->type_name("N")
        ->check(cli::wholeNumberIn(1, 1 << 20));
    app.add_option("--cache", o.cacheDir, "folder of cached references (default out/convergence-cache)")
        ->type_name("DIR");
    app.add_flag_callback("--no-flip", [&] { o.flip = false; }, "leave FLIP out (it costs the most to compute)");
    if (cli::parseCommandLine(app, std::vector<std::string>(argv + 1, argv + argc))) {
        std::fputs(app.help().c_str(), stdout);
        return std::nullopt;
    }
    if (o.adaptiveMaxSpp == 0) o.adaptiveMaxSpp = 8 * o.maxSpp;
    return o;
}

std::string sceneStem(const std::string &source) {
    if (source.rfind("builtin:", 0) == 0) return source.substr(8);
    return std::filesystem::path(source).stem().string();
}

/// The view, chosen as mvcl-render chooses it without camera options: the lens file's camera,
/// else a built-in scene's own camera, else a framing of the bounds (fov 40°).
Camera chooseCamera(const Scene &scene, const std::optional<LensStackCamera> &fileCamera, float aspect,
                    const std::string &lensFile) {
    const glm::vec3 origin(scene.worldOrigin);
    if (fileCamera && !fileCamera->sceneCamera.empty()) {
        for (std::size_t i = 0; i < scene.cameras.size(); ++i)
            if (scene.cameras[i].name == fileCamera->sceneCamera || std::to_string(i) == fileCamera->sceneCamera)
                return Camera::fromDesc(scene.cameras[i]);
        throw Error(lensFile, "camera '" + fileCamera->sceneCamera + "' is not in the scene");
    }
    if (fileCamera)
        return Camera::lookAt(fileCamera->eye - origin, fileCamera->target - origin, fileCamera->up,
                              fileCamera->verticalFovDegrees);
    if (scene.name.rfind("builtin:", 0) == 0 && !scene.cameras.empty()) return Camera::fromDesc(scene.cameras.front());
    return Camera::framing(scene.bounds(), 40.f, aspect);
}

// --- Reference cache -------------------------------------------------------------------------

/// FNV-1a, 64 bit: enough to tell cache entries apart; not a security boundary.
struct Fnv1a {
    uint64_t state = 0xcbf29ce484222325ull;
    void add(const void *data, std::size_t size) {
        const auto *bytes = static_cast<const unsigned char *>(data);
        for (std::size_t i = 0; i < size; ++i) state = (state ^ bytes[i]) * 0x100000001b3ull;
    }
    void add(const std::string &text) { add(text.data(), text.size()); }
};

std::string hex(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

/// Hash of a file's bytes; "missing" when it cannot be read.
std::string fileHash(const std::filesystem::path &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "missing";
    Fnv1a h;
    std::vector<char> buffer(1 << 16);
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        h.add(buffer.data(), std::size_t(in.gcount()));
    }
    return hex(h.state);
}

/// The loaded libmvcl: a reference rendered by other renderer code is not this renderer's
/// reference, so the library's bytes are part of the key (a rebuild that changes nothing that
/// matters costs one re-render, a stale reference would cost a wrong curve).
std::string rendererHash() {
    Dl_info info{};
    using LoadOne = mvcl::Scene (*)(std::string_view, const mvcl::SceneLoadOptions &);
    if (dladdr(reinterpret_cast<void *>(static_cast<LoadOne>(&mvcl::loadScene)), &info) == 0 || !info.dli_fname) return "unknown";
    return fileHash(info.dli_fname);
}

std::string cameraText(const Camera &c) {
    char text[256];
    std::snprintf(text, sizeof text, "eye %.9g %.9g %.9g target %.9g %.9g %.9g up %.9g %.9g %.9g fov %.9g", c.eye().x,
                  c.eye().y, c.eye().z, c.target().x, c.target().y, c.target().z, c.up().x, c.up().y, c.up().z,
                  double(c.verticalFovDegrees()));
    return text;
}

struct Reference {
    Framebuffer image;           ///< mean of the two renders
    double ownRmse = 0.0;        ///< estimated RMSE of `image` against the converged image
    double ownRelMse = 0.0;      ///< the same for relMSE (approximate: its denominator is noisy too)
    double secondsPerRender = 0.0; ///< 0 when read from the cache
    bool fromCache = false;
    std::string files;
};

// --- Sessions ----------------------------------------------------------------------------------

struct Measurement {
    std::string method;
    uint32_t seed = 0;
    int step = 0; ///< uniform: its spp; progressive and adaptive: pass number (1 = first)
    double meanSpp = 0.0;
    int minSpp = 0;
    int maxSpp = 0;
    double seconds = 0.0;
    uint64_t samples = 0; ///< pixel samples taken so far by this run (RenderPassStats::samples)
    uint64_t rays = 0;    ///< rays traced so far by this run
    double rmse = 0.0, relMse = 0.0, psnr = 0.0, flip = -1.0;
    /// The session's own estimate of relMSE (ConvergenceStats::estimatedRelativeMse), no
    /// reference needed; −1 while a pixel has fewer than two samples.
    double estimatedRelMse = -1.0;
};

/// Where a run stands after a pass.
struct Progress {
    int passes = 0;
    double seconds = 0.0; ///< wall time of its passes
    uint64_t samples = 0;
    uint64_t rays = 0;
};

struct SceneSetup {
    const Tracer *tracer = nullptr;
    Camera camera;
    const LensStack *lenses = nullptr;
    RenderSettings base; // size, threads, no preview
};

/// Runs passes until the session is idle. After every pass that did work, calls
/// onPass(session, progress); once idle, atEnd(session, progress).
template <class OnPass, class AtEnd>
void runSession(const SceneSetup &setup, const RenderSettings &settings, OnPass onPass, AtEnd atEnd) {
    RenderSession session(*setup.tracer);
    session.setCamera(setup.camera);
    session.setLensStack(*setup.lenses);
    session.setBasePolicy(RayPolicy{});
    session.setSettings(settings);
    // A session that never goes idle is a bug in it; stop well after any sane schedule.
    const int passLimit = 4 * std::max(settings.samplesPerPixel, settings.maxSamplesPerPixel) + 64;
    Progress progress;
    for (;;) {
        const Clock::time_point start = Clock::now();
        const RenderPassStats stats = session.renderPass();
        const double elapsed = secondsSince(start);
        if (stats.kind == PassKind::Idle) break;
        if (++progress.passes > passLimit)
            throw Error("RenderSession", "still not idle after " + std::to_string(passLimit) + " passes");
        if (stats.kind == PassKind::Preview || stats.wasCancelled)
            std::fprintf(stderr, "mvcl-bench: warning: pass %d was %s%s, not expected without edits\n",
                         progress.passes,
                         passKindName(stats.kind), stats.wasCancelled ? " (cancelled)" : "");
        progress.seconds += elapsed;
        progress.samples += stats.samples;
        progress.rays += stats.rays.total();
        if (!onPass(session, progress)) break;
    }
    atEnd(session, progress);
}

class Evaluator {
public:
    Evaluator(const Framebuffer &reference, bool withFlip) : m_reference(reference) {
        if (withFlip) m_flip.emplace(reference);
    }
    void measure(const Framebuffer &image, Measurement &m) const {
        m.rmse = rootMeanSquaredError(image, m_reference);
        m.relMse = relativeMeanSquaredError(image, m_reference);
        m.psnr = peakSignalToNoiseRatio(image, m_reference);
        m.flip = m_flip ? m_flip->meanError(image) : -1.0;
    }

private:
    const Framebuffer &m_reference;
    std::optional<FlipReference> m_flip;
};

Measurement sampleState(const RenderSession &session, const std::string &method, uint32_t seed, int step,
                        const Progress &progress, const Evaluator &evaluator) {
    const ConvergenceStats c = session.convergence();
    Measurement m{method, seed, step, c.meanSamples, c.minSamples, c.maxSamples, progress.seconds,
                  progress.samples, progress.rays};
    evaluator.measure(session.image(), m);
    m.estimatedRelMse = c.estimatedRelativeMse.value_or(-1.0);
    return m;
}

Framebuffer renderFixed(const SceneSetup &setup, int spp, uint32_t seed, double &seconds) {
    RenderSettings s = setup.base;
    s.sampling = SamplingMode::Fixed;
    s.samplesPerPixel = spp;
    s.seed = seed;
    Framebuffer image;
    runSession(
        setup, s, [](const RenderSession &, const Progress &) { return true; },
        [&](const RenderSession &session, const Progress &progress) {
            image = session.image();
            seconds = progress.seconds;
        });
    return image;
}

Reference makeReference(const SceneSetup &setup, const Options &o, const std::string &keyText) {
    Fnv1a h;
    h.add(keyText);
    const std::filesystem::path dir(o.cacheDir);
    const std::string stem = hex(h.state);
    const std::filesystem::path files[2] = {dir / (stem + "-a.exr"), dir / (stem + "-b.exr")};
    Reference ref;
    ref.files = (dir / (stem + "-{a,b}.exr")).string();
    Framebuffer renders[2];
    bool cached = std::filesystem::exists(files[0]) && std::filesystem::exists(files[1]);
    if (cached) {
        try {
            for (int i = 0; i < 2; ++i) renders[i] = readImage(files[i]);
            cached = renders[0].width() == o.width && renders[0].height() == o.height &&
                     renders[1].width() == o.width && renders[1].height() == o.height;
        } catch (const Error &e) {
            std::fprintf(stderr, "mvcl-bench: reference cache unreadable, rendering again: %s\n", e.what());
            cached = false;
        }
    }
    if (!cached) {
        double total = 0.0;
        for (int i = 0; i < 2; ++i) {
            double seconds = 0.0;
            renders[i] = renderFixed(setup, o.referenceSpp, kReferenceSeeds[i], seconds);
            total += seconds;
            std::fprintf(stderr, "reference %d of 2: %d spp in %.1f s\n", i + 1, o.referenceSpp, seconds);
        }
        ref.secondsPerRender = total / 2.0;
        for (int i = 0; i < 2; ++i) writeImage(files[i], renders[i]);
        std::ofstream(dir / (stem + ".txt")) << keyText; // what the entry is, for people
    }
    ref.fromCache = cached;
    ref.image = Framebuffer(o.width, o.height);
    for (std::size_t i = 0; i < ref.image.pixels().size(); ++i)
        ref.image.pixels()[i] = 0.5f * (renders[0].pixels()[i] + renders[1].pixels()[i]);
    ref.ownRmse = 0.5 * rootMeanSquaredError(renders[0], renders[1]);
    ref.ownRelMse = 0.25 * relativeMeanSquaredError(renders[0], renders[1]);
    return ref;
}

// --- Output ------------------------------------------------------------------------------------

std::string number(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

void writeCsv(const std::string &path, const std::string &scene, const Reference &ref, int referenceSpp,
              const std::vector<Measurement> &rows) {
    const std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    std::ofstream out(p);
    if (!out) throw Error(path, "cannot write");
    out << "scene,method,seed,step,mean_spp,min_spp,max_spp,seconds,rmse,relmse,psnr,flip,samples,rays,"
           "estimated_relmse\n";
    // The reference's own error estimate, so plots can show how far below the curves it lies.
    out << scene << ",reference,0," << referenceSpp << ',' << referenceSpp << ',' << referenceSpp << ','
        << referenceSpp << ',' << number(ref.secondsPerRender) << ',' << number(ref.ownRmse) << ','
        << number(ref.ownRelMse) << ",,,,,\n";
    for (const Measurement &m : rows)
        out << scene << ',' << m.method << ',' << m.seed << ',' << m.step << ',' << number(m.meanSpp) << ','
            << m.minSpp << ',' << m.maxSpp << ',' << number(m.seconds) << ',' << number(m.rmse) << ','
            << number(m.relMse) << ',' << number(m.psnr) << ',' << (m.flip >= 0.0 ? number(m.flip) : "") << ','
            << m.samples << ',' << m.rays << ',' << (m.estimatedRelMse >= 0.0 ? number(m.estimatedRelMse) : "")
            << '\n';
    if (!out) throw Error(path, "write failed");
}

/// Mean over seeds of every measured quantity, point by point: uniform's points are its spp
/// levels, a pass-wise method's are its passes. Adaptive runs of different seeds can take
/// different numbers of passes; a run that went idle keeps its final state (its image and time
/// no longer change), so every point averages all seeds.
std::vector<Measurement> meanOverSeeds(const std::vector<Measurement> &rows, const std::string &method) {
    std::map<uint32_t, std::vector<const Measurement *>> bySeed; // rows are in step order per seed
    for (const Measurement &m : rows)
        if (m.method == method) bySeed[m.seed].push_back(&m);
    std::size_t length = 0;
    for (const auto &[seed, run] : bySeed) length = std::max(length, run.size());
    const double seeds = double(bySeed.size());
    std::vector<Measurement> mean;
    for (std::size_t k = 0; k < length; ++k) {
        Measurement a{method, 0, int(k + 1)};
        a.minSpp = std::numeric_limits<int>::max();
        double psnrMse = 0.0; // PSNR is averaged as the MSE it comes from
        double flip = 0.0;
        bool haveFlip = true;
        for (const auto &[seed, run] : bySeed) {
            const Measurement &m = *run[std::min(k, run.size() - 1)];
            if (method == "uniform") a.step = m.step;
            a.meanSpp += m.meanSpp / seeds;
            a.minSpp = std::min(a.minSpp, m.minSpp);
            a.maxSpp = std::max(a.maxSpp, m.maxSpp);
            a.seconds += m.seconds / seeds;
            a.rmse += m.rmse / seeds;
            a.relMse += m.relMse / seeds;
            psnrMse += std::pow(10.0, -m.psnr / 10.0) / seeds;
            flip += m.flip / seeds;
            haveFlip = haveFlip && m.flip >= 0.0;
        }
        a.psnr = psnrMse > 0.0 ? -10.0 * std::log10(psnrMse) : std::numeric_limits<double>::infinity();
        a.flip = haveFlip ? flip : -1.0; // −1: FLIP was not computed
        mean.push_back(a);
    }
    return mean;
}

void printRow(const Measurement &m, const char *stepLabel) {
    std::printf("%-12s %6s %-5d %8.2f %5d %5d %9.3f %11.4e %11.4e %7.2f %8s\n", m.method.c_str(), stepLabel, m.step,
                m.meanSpp, m.minSpp, m.maxSpp, m.seconds, m.rmse, m.relMse, m.psnr,
                m.flip >= 0.0 ? number(m.flip).c_str() : "-");
}

/// Uniform: every spp. Pass-wise methods: the first pass whose mean spp reaches each power of
/// two, and the last pass.
void printTable(const std::map<std::string, std::vector<Measurement>> &means) {
    std::printf("\n%-12s %6s %-5s %8s %5s %5s %9s %11s %11s %7s %8s\n", "method", "", "step", "mean spp", "min",
                "max", "seconds", "rmse", "relmse", "psnr", "flip");
    for (const char *method : {"uniform", "progressive", "adaptive"}) {
        const auto found = means.find(method);
        if (found == means.end()) continue;
        const std::vector<Measurement> &curve = found->second;
        double nextPower = 1.0;
        for (std::size_t i = 0; i < curve.size(); ++i) {
            const bool uniform = std::string(method) == "uniform";
            const bool last = i + 1 == curve.size();
            if (!uniform && !last && curve[i].meanSpp < nextPower) continue;
            while (nextPower <= curve[i].meanSpp) nextPower *= 2.0;
            printRow(curve[i], uniform ? "spp" : "pass");
        }
    }
}

/// How the session's own estimate of relMSE compares with the error measured against the
/// reference (less the reference's own error, which the measured one includes), per method over
/// every measurement of every seed that has an estimate.
void printEstimateAgainstError(const std::vector<Measurement> &rows, const Reference &ref) {
    std::printf("\nestimated relMSE (no reference) over the error against the reference, every measurement:\n");
    for (const char *method : {"uniform", "progressive", "adaptive"}) {
        double lowest = std::numeric_limits<double>::infinity(), highest = 0.0, logSum = 0.0;
        int count = 0;
        for (const Measurement &m : rows) {
            if (m.method != method || m.estimatedRelMse < 0.0) continue;
            const double truth = m.relMse - ref.ownRelMse;
            if (!(truth > 0.0)) continue;
            const double ratio = m.estimatedRelMse / truth;
            lowest = std::min(lowest, ratio);
            highest = std::max(highest, ratio);
            logSum += std::log(ratio);
            ++count;
        }
        if (count == 0) continue;
        std::printf("%-12s %.2f .. %.2f (geometric mean %.2f, %d measurements)\n", method, lowest, highest,
                    std::exp(logSum / count), count);
    }
}

/// Per seed: where adaptive first reaches that seed's uniform relMSE at `finalSpp`, in time and
/// in rays, each over uniform's, and its mean spp there. Rays show what the schedule buys,
/// apart from what a ray costs: uniform's rays are mostly cheap misses of the background,
/// adaptive's mostly hit the model.
void printPerSeedRatios(const std::vector<Measurement> &rows, int finalSpp) {
    std::printf("\nper seed: adaptive at the seed's uniform final relMSE, time and rays over uniform's, mean spp\n");
    for (const Measurement &u : rows) {
        if (u.method != "uniform" || u.step != finalSpp) continue;
        Curve byTime, byRays, bySpp;
        for (const Measurement &m : rows)
            if (m.method == "adaptive" && m.seed == u.seed) {
                byTime.push_back({m.seconds, m.relMse});
                byRays.push_back({double(m.rays), m.relMse});
                bySpp.push_back({m.meanSpp, m.relMse});
            }
        const std::optional<Crossing> time = firstCrossing(byTime, u.relMse), rays = firstCrossing(byRays, u.relMse),
                                      spp = firstCrossing(bySpp, u.relMse);
        if (!time || !rays || !spp) {
            std::printf("seed %u: never reaches it\n", u.seed);
            continue;
        }
        std::printf("seed %u: R %.3f in time, %.3f in rays, %.1f spp\n", u.seed, time->seconds / u.seconds,
                    rays->seconds / double(u.rays), spp->seconds);
    }
}

Curve relMseCurve(const std::vector<Measurement> &mean) {
    Curve c;
    for (const Measurement &m : mean) c.push_back({m.seconds, m.relMse});
    return c;
}

/// "reaches E in R× the time" for one method's mean curve against uniform's final point.
std::string crossingText(const std::vector<Measurement> &mean, const Measurement &uniformFinal, bool &reached) {
    const std::optional<Crossing> cross = firstCrossing(relMseCurve(mean), uniformFinal.relMse);
    char text[256];
    reached = cross.has_value();
    if (!cross) {
        // It would take at least as long as it ran: a lower bound, whatever its size.
        const Measurement &last = mean.back();
        std::snprintf(text, sizeof text, ">%.3g", last.seconds / uniformFinal.seconds);
    } else {
        std::snprintf(text, sizeof text, "%s%.3g", cross->atFirstPoint ? "<=" : "",
                      cross->seconds / uniformFinal.seconds);
    }
    return text;
}

} // namespace

int runConvergenceBench(int argc, char **argv) {
    try {
        std::optional<Options> parsed = parseOptions(argc, argv);
        if (!parsed) return 0;
        Options &o = *parsed;
        LensRegistry registry;
        for (const Error &skipped : registry.loadModules(LensRegistry::defaultSearchPath()))
            std::fprintf(stderr, "mvcl-bench: warning: plugin skipped: %s\n", skipped.what());

        if (o.model.empty() && o.lensFile.empty()) {
            if (std::filesystem::exists(kDefaultLensFile))
                o.lensFile = kDefaultLensFile;
            else
                o.model = "builtin:cube-in-cube";
        }
        LensStackDescription lenses;
        if (!o.lensFile.empty()) lenses = readLensStackFile(o.lensFile, registry);
        const std::string source = o.model.empty() ? lenses.scene : o.model;
        if (source.empty()) throw Error(o.lensFile, "names no scene, and none was given");
        lenses.scene = source;

        SceneLoadOptions loadOptions;
        loadOptions.layerRules = lenses.layerRules;
        const Scene scene = loadScene(source, loadOptions);
        const Tracer tracer(scene);

        SceneSetup setup;
        setup.tracer = &tracer;
        setup.camera = chooseCamera(scene, lenses.camera, float(o.width) / float(o.height), o.lensFile);
        setup.lenses = &lenses.lenses;
        setup.base.width = o.width;
        setup.base.height = o.height;
        setup.base.threads = o.threads;
        setup.base.previewBudgetSeconds = 0.0; // no camera moves here: never a reduced preview
        setup.base.targetError = 0.f;
        setup.base.timeLimitSeconds = 0.0;

        const std::string name = sceneStem(source);
        const std::string lensText = lenses.lenses.isEmpty() ? "no lenses"
                                                             : std::to_string(lenses.lenses.size()) + " lenses from " +
                                                                   o.lensFile;
        std::printf("scene      %s (%zu triangles), %s\n", source.c_str(), tracer.buildStats().triangles,
                    lensText.c_str());
        std::printf("view       %dx%d, %s threads; %d seeds, up to %d spp; adaptive: target error %g, %d to %d spp\n",
                    o.width, o.height, o.threads ? std::to_string(o.threads).c_str() : "all", o.seeds, o.maxSpp,
                    double(o.adaptiveError), o.adaptiveMin, o.adaptiveMaxSpp);

        // Everything the reference depends on.
        const bool isFile = source.rfind("builtin:", 0) != 0;
        std::string key = "mvcl-bench convergence reference v1\nsource " + source + "\n";
        if (isFile) key += "scene file " + fileHash(source) + "\n";
        key += "renderer " + rendererHash() + "\ncamera " + cameraText(setup.camera) + "\nsize " +
               std::to_string(o.width) + "x" + std::to_string(o.height) + "\nreference spp " +
               std::to_string(o.referenceSpp) + "\nseeds " + std::to_string(kReferenceSeeds[0]) + " " +
               std::to_string(kReferenceSeeds[1]) + "\nlenses " + lensStackJson(lenses) + "\n";
        // The plugins' code shapes the image as much as the library's.
        for (const std::shared_ptr<Lens> &lens : lenses.lenses.lenses()) {
            const std::string origin = registry.origin(lens->typeName());
            key += "plugin " + lens->typeName() + " " + fileHash(origin) + "\n";
        }
        const Reference ref = makeReference(setup, o, key);
        if (ref.fromCache)
            std::printf("reference  %d spp x 2 seeds, cached: %s\n", o.referenceSpp, ref.files.c_str());
        else
            std::printf("reference  %d spp x 2 seeds, %.1f s per render, cached as %s\n", o.referenceSpp,
                        ref.secondsPerRender, ref.files.c_str());
        std::printf("reference  own error (half the difference of the two): RMSE %.3e, relMSE %.3e\n", ref.ownRmse,
                    ref.ownRelMse);

        const Evaluator evaluator(ref.image, o.flip);
        std::vector<Measurement> rows;
        auto report = [](const Measurement &m) {
            std::fprintf(stderr, "%-11s seed %u %s %4d: %7.3f s, mean %.1f spp, relMSE %.3e\n", m.method.c_str(),
                         m.seed, m.method == "uniform" ? "spp " : "pass", m.step, m.seconds, m.meanSpp, m.relMse);
        };
        int uniformFinalSpp = 1;
        while (uniformFinalSpp * 2 <= o.maxSpp) uniformFinalSpp *= 2;
        if (uniformFinalSpp != o.maxSpp)
            std::fprintf(stderr, "mvcl-bench: note: --max-spp %d is not a power of two; uniform stops at %d\n",
                         o.maxSpp, uniformFinalSpp);
        // Seeds outermost, so that a drift of the machine's speed during the run touches all
        // three methods alike.
        for (int s = 1; s <= o.seeds; ++s) {
            const uint32_t seed = uint32_t(s);
            double uniformFinal = 0.0; // this seed's relMSE at uniformFinalSpp
            for (int spp = 1; spp <= o.maxSpp; spp *= 2) {
                RenderSettings settings = setup.base;
                settings.sampling = SamplingMode::Fixed;
                settings.samplesPerPixel = spp;
                settings.seed = seed;
                runSession(
                    setup, settings, [](const RenderSession &, const Progress &) { return true; },
                    [&](const RenderSession &session, const Progress &progress) {
                        rows.push_back(sampleState(session, "uniform", seed, spp, progress, evaluator));
                        report(rows.back());
                        if (spp == uniformFinalSpp) uniformFinal = rows.back().relMse;
                        if (rows.back().minSpp != spp || rows.back().maxSpp != spp)
                            std::fprintf(stderr,
                                         "mvcl-bench: warning: Fixed %d spp ended with %d..%d samples per pixel\n",
                                         spp, rows.back().minSpp, rows.back().maxSpp);
                    });
            }
            for (const SamplingMode mode : {SamplingMode::Progressive, SamplingMode::Adaptive}) {
                const std::string method = mode == SamplingMode::Progressive ? "progressive" : "adaptive";
                RenderSettings settings = setup.base;
                settings.sampling = mode;
                settings.samplesPerPixel = 1;
                const bool adaptive = mode == SamplingMode::Adaptive;
                settings.maxSamplesPerPixel = adaptive ? o.adaptiveMaxSpp : o.maxSpp;
                settings.minSamplesPerPixel = o.adaptiveMin;
                settings.targetError = adaptive ? o.adaptiveError : 0.f;
                settings.seed = seed;
                runSession(
                    setup, settings,
                    [&](const RenderSession &session, const Progress &progress) {
                        rows.push_back(sampleState(session, method, seed, progress.passes, progress, evaluator));
                        // Past uniform's final error with a margin, adaptive's curve has shown
                        // what R needs; its samples up to the cap would only cost bench time.
                        return !adaptive || rows.back().relMse > 0.5 * uniformFinal;
                    },
                    [&](const RenderSession &, const Progress &) { report(rows.back()); });
            }
        }

        const std::string csv = o.csv.empty() ? "out/convergence-" + name + ".csv" : o.csv;
        writeCsv(csv, name, ref, o.referenceSpp, rows);

        std::map<std::string, std::vector<Measurement>> means;
        for (const char *method : {"uniform", "progressive", "adaptive"})
            means[method] = meanOverSeeds(rows, method);
        printTable(means);
        std::printf("\nwrote      %s (%zu measurements)\n", csv.c_str(), rows.size());
        printEstimateAgainstError(rows, ref);

        const std::vector<Measurement> &uniform = means["uniform"];
        const auto finalUniform = std::find_if(uniform.begin(), uniform.end(),
                                               [&](const Measurement &m) { return m.step == uniformFinalSpp; });
        if (finalUniform == uniform.end() || means["adaptive"].empty() || means["progressive"].empty())
            throw Error("convergence", "missing measurements");
        std::printf("reference  own relMSE %.3e is %.2g%% of uniform's final relMSE %.3e\n", ref.ownRelMse,
                    100.0 * ref.ownRelMse / finalUniform->relMse, finalUniform->relMse);
        // Time to reach uniform's relMSE at each of its spp levels, over uniform's time there.
        std::printf("\ntime to reach uniform's relMSE at its spp, over uniform's time (mean curves, log-log)\n%-12s",
                    "spp");
        for (const Measurement &u : uniform) std::printf(" %7d", u.step);
        std::printf("\n");
        for (const char *method : {"progressive", "adaptive"}) {
            std::printf("%-12s", method);
            for (const Measurement &u : uniform) {
                bool reached = false;
                std::printf(" %7s", crossingText(means[method], u, reached).c_str());
            }
            std::printf("\n");
        }

        const std::vector<Measurement> &adaptiveMean = means["adaptive"];
        const Measurement best = *std::min_element(
            adaptiveMean.begin(), adaptiveMean.end(),
            [](const Measurement &a, const Measurement &b) { return a.relMse < b.relMse; });
        bool reached = false;
        const std::string ratio = crossingText(adaptiveMean, *finalUniform, reached);
        std::printf("\n%s: adaptive reaches uniform's final error in %s× the time", name.c_str(), ratio.c_str());
        if (!reached) {
            // Adaptive takes the same samples as uniform, only fewer of them where it stopped, so
            // its final error is uniform's plus what the stopped pixels still lack: say how close.
            Measurement withinOnePercent = *finalUniform;
            withinOnePercent.relMse *= 1.01;
            bool nearlyReached = false;
            const std::string nearly = crossingText(adaptiveMean, withinOnePercent, nearlyReached);
            std::printf(" (it never does: its lowest relMSE, %.4e after %.3f s, is %.2g%% above uniform's %.4e; "
                        "the bound is its total time; within 1%%: %s×)",
                        best.relMse, best.seconds, 100.0 * (best.relMse / finalUniform->relMse - 1.0),
                        finalUniform->relMse, nearly.c_str());
        }
        std::printf("\n");
        printPerSeedRatios(rows, uniformFinalSpp);
        return 0;
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-bench: %s\n", e.what());
        return e.source() == "command line" ? 2 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "mvcl-bench: internal error: %s\n", e.what());
        return 4;
    }
}

} // namespace mvcl::bench
