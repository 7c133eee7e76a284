// PixelProbe built from a LensContext composes every lens as a render of that view shows it
// (Lens::snapshotIn, as RenderSession does), so a lens that depends on the camera behaves the
// same under the probe as in an image; built from a size alone it keeps committed snapshots.
// Also its per-lens weights, and the depth histogram's surroundings in the same context.

#include <mvcl/lens/LensStack.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/DepthHistogram.h>
#include <mvcl/view/PixelProbe.h>
#include <mvcl/view/ViewLensContext.h>

#include <gtest/gtest.h>

#include <memory>

namespace mvcl {
namespace {

constexpr int kWidth = 40, kHeight = 30;

/// Tints by where the camera is: its colour offset is 0.01 × the eye (scene space), so it
/// follows the view, and says so (dependsOnView).
class EyeTintLens : public Lens {
public:
    static const LensInfo &typeInfo() {
        static const LensInfo info{"test-eye-tint", "Offsets the colour by the camera position.", {}, kAllRayTypes,
                                   LensAlgebra{}, true};
        return info;
    }
    EyeTintLens() : Lens(typeInfo()) {}

protected:
    LensContribution contribute(const PropertyValues &, const LensRegion &, const LensContext &context) const override {
        LensContribution contribution;
        contribution.color.offset = 0.01f * context.camera.eye;
        return contribution;
    }
};

std::shared_ptr<Lens> committed(std::shared_ptr<Lens> lens, const LensRegion &region) {
    lens->setRegion(region);
    lens->commit();
    return lens;
}

struct View {
    Scene scene = makeBuiltinScene("cube-in-cube");
    Tracer tracer{scene};
    Camera camera = Camera::fromDesc(scene.cameras.front());
};

TEST(PixelProbe, InAContextLensesContributeForThatViewAsInARender) {
    const View view;
    LensStack stack;
    stack.add(committed(std::make_shared<EyeTintLens>(), LensRegion::rectangle({0.5f, 0.5f}, {1.f, 1.f})));
    const LensContext context = lensContextOf(view.scene, view.camera, kWidth, kHeight);

    const PixelProbe probe(stack, context);
    EXPECT_EQ(probe.map().width(), kWidth);
    EXPECT_EQ(probe.map().height(), kHeight);
    const glm::vec3 expected = 0.01f * view.camera.eye();
    EXPECT_EQ(probe.policy(20, 15).ray.color.offset, expected);
    EXPECT_EQ(probe.policy(20, 15).ray.color, stack.lens(0)->snapshotIn(context)->contribution.color);

    // Without a context the lens keeps what it committed in its own (no view known: default eye).
    const PixelProbe committedOnly(stack, kWidth, kHeight);
    EXPECT_EQ(committedOnly.policy(20, 15).ray.color.offset, 0.01f * CameraDesc{}.eye);
    EXPECT_NE(committedOnly.policy(20, 15).ray.color.offset, expected);

    // Another camera, another tint: the probe follows the view without a commit.
    const Camera moved = Camera::lookAt(view.camera.eye() + glm::vec3(3.f, 0.f, 0.f), view.camera.target(),
                                        view.camera.up(), view.camera.verticalFovDegrees());
    const PixelProbe elsewhere(stack, lensContextOf(view.scene, moved, kWidth, kHeight));
    EXPECT_EQ(elsewhere.policy(20, 15).ray.color.offset, 0.01f * moved.eye());
}

TEST(PixelProbe, LensWeightsAreOneInsideZeroOutsideAndBlendOnAFeatheredEdge) {
    const View view;
    LensRegion feathered = LensRegion::ellipse({0.5f, 0.5f}, {0.5f, 0.5f});
    feathered.setFeather(4.f);
    LensStack stack;
    stack.add(committed(std::make_shared<EyeTintLens>(), LensRegion::rectangle({0.25f, 0.5f}, {0.5f, 1.f})));
    stack.add(committed(std::make_shared<EyeTintLens>(), feathered));
    const PixelProbe probe(stack, lensContextOf(view.scene, view.camera, kWidth, kHeight));

    EXPECT_FLOAT_EQ(probe.lensWeight(0, 5, 15), 1.f);
    EXPECT_FLOAT_EQ(probe.lensWeight(1, 5, 15), 0.f);
    EXPECT_FLOAT_EQ(probe.lensWeight(0, 35, 15), 0.f);
    EXPECT_FLOAT_EQ(probe.lensWeight(1, 20, 15), 1.f);
    ASSERT_EQ(probe.lenses(15, 15).size(), 2u) << "both lenses over the left half of the ellipse";
    EXPECT_EQ(probe.lenses(15, 15)[0].lensIndex, 0);
    EXPECT_EQ(probe.lenses(15, 15)[1].lensIndex, 1);
    EXPECT_TRUE(probe.lenses(39, 0).empty());
    EXPECT_FLOAT_EQ(probe.lensWeight(5, 20, 15), 0.f) << "no such lens";
    EXPECT_FLOAT_EQ(probe.lensWeight(-1, 20, 15), 0.f);

    int edgePixels = 0;
    for (int x = 20; x < kWidth; ++x) {
        const float w = probe.lensWeight(1, x, 15);
        if (w > 0.f && w < 1.f) {
            ++edgePixels;
            float sum = 0.f;
            for (const PolicyTerm &term : probe.terms(x, 15))
                if (probe.map().policy(term.policy).lensSet & 2u) sum += term.weight;
            EXPECT_FLOAT_EQ(w, sum);
            ASSERT_EQ(probe.lenses(x, 15).size(), 1u);
            EXPECT_FLOAT_EQ(probe.lenses(x, 15)[0].weight, w);
        }
    }
    EXPECT_GT(edgePixels, 0) << "the feather band crosses the middle row";
}

TEST(DepthHistogram, SurroundingLensesAreComposedInTheRequestsView) {
    const View view;
    LensStack stack;
    stack.add(committed(std::make_shared<EyeTintLens>(), LensRegion::rectangle({0.5f, 0.5f}, {1.f, 1.f})));
    stack.add(committed(std::make_shared<EyeTintLens>(), LensRegion::ellipse({0.5f, 0.5f}, {0.3f, 0.3f})));
    const DepthHistogramRequest request =
        depthHistogramRequest(view.tracer, stack, 1, {}, view.camera, kWidth, kHeight);
    ASSERT_TRUE(request.surroundings);
    EXPECT_EQ(request.surroundings->dominantPolicy(20, 15).ray.color.offset, 0.01f * view.camera.eye())
        << "the other lens as this view shows it, not as committed without one";
}

} // namespace
} // namespace mvcl
