#include "AnimationCommand.h"

#include "ProgressBar.h"

#include <mvcl/controller/AnimationPlayer.h>
#include <mvcl/controller/ViewCoordinates.h>
#include <mvcl/core/Error.h>
#include <mvcl/io/AnimationFile.h>
#include <mvcl/lens/PolicyMap.h>
#include <mvcl/view/FrameWriter.h>
#include <mvcl/view/LensOutlines.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <optional>
#include <unistd.h>

namespace mvcl::cli {

namespace {

volatile std::sig_atomic_t interruptRequested = 0;

extern "C" void requestInterrupt(int) { interruptRequested = 1; }

} // namespace

Animation commandLineAnimation(const RenderCommandLine &cl, const LensStack &lenses) {
    Animation animation;
    if (!cl.animationFile.empty()) {
        animation = readAnimationFile(cl.animationFile, lenses);
    } else {
        const double rate = cl.frameRate.value_or(30.0);
        if (cl.turntableFrames) {
            animation = Animation::turntable(*cl.turntableFrames, rate);
        } else {
            animation.setFrameRate(rate);
            animation.setDuration(double(cl.frameCount) / rate);
        }
        for (const std::string &spec : cl.sweeps) {
            try {
                addSweepSpec(animation, spec, lenses);
            } catch (const Error &e) { // a bad option value: exit 2
                throw Error("command line", e.what());
            }
        }
    }
    if (cl.frameRate && !cl.animationFile.empty()) animation.setFrameRate(*cl.frameRate);
    if (cl.frameRange && cl.frameRange->second >= animation.frameCount())
        throw Error("command line", "--frames " + std::to_string(cl.frameRange->first) + "-" +
                                        std::to_string(cl.frameRange->second) + ": the animation has " +
                                        std::to_string(animation.frameCount()) + " frames (0 to " +
                                        std::to_string(animation.frameCount() - 1) + ")");
    return animation;
}

int renderAnimation(const RenderCommandLine &cl, const Animation &animation, RenderSession &session,
                    const LensStack &lenses, const Camera &camera, const Scene &scene, const std::string &output) {
    const int first = cl.frameRange ? cl.frameRange->first : 0;
    const int last = cl.frameRange ? cl.frameRange->second : animation.frameCount() - 1;
    std::optional<FrameWriter> writer;
    try {
        writer.emplace(output, cl.width, cl.height, animation.frameRate());
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return kExitOutput;
    }
    // Ctrl+C ends the render after the frame in progress: every frame file written is whole,
    // and a video gets its index, so it plays up to there.
    std::signal(SIGINT, requestInterrupt);
    std::signal(SIGTERM, requestInterrupt);

    AnimationPlayer player(animation, lenses, camera, ViewCoordinates({cl.width, cl.height}, scene));
    const int frames = last - first + 1;
    ProgressBar bar(cl.progress && isatty(STDERR_FILENO));
    int done = 0;
    session.setProgressCallback([&](float f) { bar.update((float(done) + f) / float(frames)); });
    double milliseconds = 0.0, writeMilliseconds = 0.0;
    uint64_t raysTotal = 0, pixelsTraced = 0;
    int fullFrames = 0, incrementalFrames = 0;
    for (int frame = first; frame <= last && !interruptRequested; ++frame) {
        bar.setLabel("frame " + std::to_string(frame - first + 1) + "/" + std::to_string(frames));
        session.setCamera(player.showFrame(frame));
        session.setLensStack(lenses); // the session looks at the lenses' new snapshots
        const RenderPassStats stats = session.renderUntilIdle();
        LensStack::checkClipVolumes(session.policyMap());
        milliseconds += stats.milliseconds;
        raysTotal += stats.rays.total();
        pixelsTraced += stats.pixelsTraced;
        (stats.kind == PassKind::Full ? fullFrames : incrementalFrames) += 1;
        Framebuffer image = session.image();
        drawLensOutlines(lenses, image);
        try {
            const auto writeStart = std::chrono::steady_clock::now();
            writer->write(frame, image);
            writeMilliseconds += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - writeStart).count();
        } catch (const Error &e) {
            bar.finish();
            std::fprintf(stderr, "mvcl-render: %s\n", e.what());
            return kExitOutput;
        }
        ++done;
    }
    bar.finish();
    try {
        const auto finishStart = std::chrono::steady_clock::now(); // a video's encoder holds frames back
        writer->finish();
        writeMilliseconds += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - finishStart).count();
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return kExitOutput;
    }
    std::printf("scene      %s\n", scene.name.c_str());
    std::printf("animation  %d frames at %g fps (%.3g s); rendered %d to %d\n", animation.frameCount(),
                animation.frameRate(), animation.duration(), first, first + done - 1);
    std::printf("render     %dx%d, %d spp: %.1f ms for %d frames (%.1f ms each); %d full, %d re-traced only "
                "what their lenses changed; %.3f M pixels traced, %.3f M rays\n",
                cl.width, cl.height, session.settings().samplesPerPixel, milliseconds, done,
                done > 0 ? milliseconds / done : 0.0, fullFrames, incrementalFrames, double(pixelsTraced) * 1e-6,
                double(raysTotal) * 1e-6);
    if (writer->writesVideo()) std::printf("wrote      %s in %.1f ms (encoding)\n", output.c_str(), writeMilliseconds);
    else if (done > 0)
        std::printf("wrote      %s .. %s in %.1f ms (encoding)\n", FrameWriter::frameFileName(output, first).c_str(),
                    FrameWriter::frameFileName(output, first + done - 1).c_str(), writeMilliseconds);
    if (interruptRequested) {
        std::fprintf(stderr, "mvcl-render: interrupted after %d of %d frames; the frames written are complete\n", done,
                     frames);
        return kExitInterrupted;
    }
    return kExitOk;
}

} // namespace mvcl::cli
