// RenderSession::setRefinementHeld: a held session still runs the passes edits ask for, but
// refines an image already complete at full resolution only once released.

#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <gtest/gtest.h>

namespace mvcl {
namespace {

TEST(RefinementHoldTest, AHeldSessionAnswersEditsButRefinesOnlyWhenReleased) {
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

} // namespace
} // namespace mvcl
