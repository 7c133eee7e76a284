// How render sessions of several views share the cores: setRefinementHeld (a held session
// still runs the passes edits ask for, but refines a complete image only once released), and a
// RenderPassGate (sessions take turns; their images are the same as alone, and an edit of one
// gets through while another refines).

#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace mvcl {
namespace {

TEST(RenderPriorityTest, AHeldSessionAnswersEditsButRefinesOnlyWhenReleased) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    RenderSettings settings;
    settings.width = 48;
    settings.height = 32;
    settings.sampling = SamplingMode::Progressive;
    settings.maxSamplesPerPixel = 8;
    settings.previewBudgetSeconds = 0.0;
    RenderSession session(tracer);
    session.setSettings(settings);
    session.setCamera(Camera::fromDesc(scene.cameras.front()));
    session.setRefinementHeld(true);
    EXPECT_TRUE(session.isRefinementHeld());
    EXPECT_EQ(session.renderPass().kind, PassKind::Full); // asked for by the edits
    EXPECT_FALSE(session.hasWork());                      // refinement waits
    EXPECT_EQ(session.renderPass().kind, PassKind::Idle);

    const Camera first = Camera::fromDesc(scene.cameras.front());
    session.setCamera(Camera::lookAt({0.f, 2.f, 8.f}, first.target(), first.up(), first.verticalFovDegrees()));
    EXPECT_TRUE(session.hasWork()); // an edit is always served
    EXPECT_EQ(session.renderPass().kind, PassKind::Full);
    EXPECT_FALSE(session.hasWork());

    session.setRefinementHeld(false);
    EXPECT_TRUE(session.hasWork());
    EXPECT_EQ(session.renderPass().kind, PassKind::Refine);
    session.renderUntilIdle();
    EXPECT_EQ(session.convergence().minSamples, 8);
}

/// Waits (60 s at most, a safety net, not a speed check) until `session` has no work.
bool waitIdle(const RenderSession &session) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (session.hasWork())
        if (std::chrono::steady_clock::now() > end) return false;
        else std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return true;
}

TEST(RenderPriorityTest, SessionsSharingAGateRenderTheSameImagesAsAloneAndEditsGetThroughRefinement) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.sampling = SamplingMode::Progressive;
    settings.maxSamplesPerPixel = 16;
    settings.previewBudgetSeconds = 0.0;
    const Camera first = Camera::fromDesc(scene.cameras.front());
    const Camera second = Camera::lookAt({3.f, 2.f, 6.f}, first.target(), first.up(), first.verticalFovDegrees());

    const auto reference = [&](const Camera &camera) {
        RenderSession alone(tracer);
        alone.setSettings(settings);
        alone.setCamera(camera);
        alone.renderUntilIdle();
        return alone.image();
    };
    const Framebuffer expected = reference(second);

    const std::shared_ptr<RenderPassGate> gate = RenderSession::makePassGate();
    RenderSession a(tracer), b(tracer);
    RenderSettings longRefinement = settings;
    longRefinement.maxSamplesPerPixel = 1 << 20; // b refines for as long as the test runs
    for (RenderSession *session : {&a, &b}) session->setPassGate(gate);
    a.setSettings(settings);
    b.setSettings(longRefinement);
    a.setCamera(first);
    b.setCamera(first);
    a.start();
    b.start();
    for (int edit = 0; edit < 20; ++edit) { // a's edits arrive while b refines
        a.setCamera(edit % 2 ? second : first); // the last one: second
        std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
    ASSERT_TRUE(waitIdle(a));
    // b: the budget of the reference, from a fresh start (its refined samples are past it).
    b.setSettings(settings);
    b.setCamera(second);
    ASSERT_TRUE(waitIdle(b));
    a.stop();
    b.stop();
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) {
            ASSERT_EQ(a.image().at(x, y), expected.at(x, y)) << x << "," << y;
            ASSERT_EQ(b.image().at(x, y), expected.at(x, y)) << x << "," << y;
        }
}

} // namespace
} // namespace mvcl
