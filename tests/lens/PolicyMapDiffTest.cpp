// markChangedPixels: after a lens edit exactly the pixels whose policies or weights changed are
// marked, whatever the lens sets are called and in which order the policies were met.
#include <mvcl/lens/PolicyMapDiff.h>

#include "lens/FixedLens.h"

#include <mvcl/core/Error.h>
#include <mvcl/lens/LensStack.h>

#include <gtest/gtest.h>

#include <vector>

using namespace mvcl;
using test::makeFixedLens;

namespace {

constexpr int kWidth = 240, kHeight = 160;
const PixelRect kWholeView{0, 0, kWidth, kHeight};

LensContribution layerMask(uint32_t mask) {
    LensContribution c;
    c.visibility[size_t(RayType::Primary)].layerMask = mask;
    return c;
}

LensContribution colorMatrix(const glm::mat3 &matrix) {
    LensContribution c;
    c.color.matrix = matrix;
    return c;
}

LensRegion featheredEllipse(const glm::vec2 &center, const glm::vec2 &size, float feather) {
    LensRegion region = LensRegion::ellipse(center, size);
    region.setFeather(feather);
    return region;
}

float coverageAt(const LensRegion &region, int x, int y) {
    return region.coverage({float(x) + 0.5f, float(y) + 0.5f}, kWidth, kHeight);
}

std::vector<uint8_t> changedPixels(const PolicyMap &before, const PolicyMap &after, int threads = 2) {
    std::vector<uint8_t> changed;
    markChangedPixels(before, after, kWholeView, changed, threads);
    return changed;
}

/// Pixels where `predicate(x, y)` holds, as a mask like markChangedPixels's.
template <class Predicate> std::vector<uint8_t> maskWhere(Predicate predicate) {
    std::vector<uint8_t> mask(size_t(kWidth) * kHeight, 0);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) mask[size_t(y) * kWidth + size_t(x)] = predicate(x, y) ? 1 : 0;
    return mask;
}

size_t countOf(const std::vector<uint8_t> &mask) { return size_t(std::count(mask.begin(), mask.end(), uint8_t(1))); }

::testing::AssertionResult sameMasks(const std::vector<uint8_t> &expected, const std::vector<uint8_t> &actual) {
    if (expected.size() != actual.size()) return ::testing::AssertionFailure() << "sizes differ";
    for (size_t i = 0; i < expected.size(); ++i)
        if (expected[i] != actual[i])
            return ::testing::AssertionFailure() << "pixel (" << i % kWidth << ", " << i / kWidth << "): expected "
                                                 << int(expected[i]) << ", got " << int(actual[i]);
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(PolicyMapDiff, AMovedLensChangesOnlyTheCrescentAndTheFeatheredEdges) {
    const LensRegion from = featheredEllipse({0.45f, 0.5f}, {0.6f, 0.7f}, 6.f);
    LensRegion to = from;
    to.setCenter({0.47f, 0.5f}); // 4.8 px to the right
    auto lens = makeFixedLens(layerMask(layerBit(1)), from);
    LensStack stack;
    stack.add(lens);
    const PolicyMap before = stack.compose(RayPolicy{}, kWidth, kHeight);
    lens->setRegion(to);
    lens->commit();
    const PolicyMap after = stack.compose(RayPolicy{}, kWidth, kHeight);

    const std::vector<uint8_t> changed = changedPixels(before, after);
    // A pixel renders the same exactly when the lens covers it as much as before.
    EXPECT_TRUE(sameMasks(maskWhere([&](int x, int y) { return coverageAt(from, x, y) != coverageAt(to, x, y); }),
                          changed));
    const size_t footprint = countOf(maskWhere([&](int x, int y) { return coverageAt(to, x, y) > 0.f; }));
    EXPECT_GT(countOf(changed), 0u);
    EXPECT_LT(countOf(changed), footprint / 2) << "the inside, fully covered before and after, stays";
}

TEST(PolicyMapDiff, APropertyChangeChangesTheWholeFootprint) {
    const LensRegion region = featheredEllipse({0.5f, 0.5f}, {0.5f, 0.6f}, 5.f);
    auto lens = makeFixedLens(layerMask(layerBit(1)), region);
    LensStack stack;
    stack.add(lens);
    const PolicyMap before = stack.compose(RayPolicy{}, kWidth, kHeight);
    lens->setContribution(layerMask(layerBit(2)));
    lens->commit();
    const PolicyMap after = stack.compose(RayPolicy{}, kWidth, kHeight);
    EXPECT_TRUE(sameMasks(maskWhere([&](int x, int y) { return coverageAt(region, x, y) > 0.f; }),
                          changedPixels(before, after)));
}

TEST(PolicyMapDiff, ReorderingCommutingLensesChangesNothing) {
    // Visibility constraints intersect, which commutes exactly. The lens sets swap their bits
    // and the policies their table order; neither counts. (Feathered edges must not cross:
    // where two lenses are both partial, the order of the blended terms is the stack order.)
    LensStack stack;
    stack.add(makeFixedLens(layerMask(layersFrom(1)), featheredEllipse({0.4f, 0.5f}, {0.5f, 0.7f}, 8.f)));
    stack.add(makeFixedLens(layerMask(layerBit(0) | layerBit(2)), LensRegion::rectangle({0.6f, 0.5f}, {0.4f, 0.4f})));
    const PolicyMap before = stack.compose(RayPolicy{}, kWidth, kHeight);
    stack.move(1, 0);
    const PolicyMap after = stack.compose(RayPolicy{}, kWidth, kHeight);
    ASSERT_NE(before.policy(1).lensSet, after.policy(1).lensSet) << "the test must reorder the table";
    EXPECT_EQ(countOf(changedPixels(before, after)), 0u);
}

TEST(PolicyMapDiff, ReorderingCommutingLensesChangesOnlyWhereTheirFeathersCross) {
    const LensRegion a = featheredEllipse({0.4f, 0.5f}, {0.5f, 0.7f}, 8.f);
    const LensRegion b = featheredEllipse({0.6f, 0.5f}, {0.5f, 0.7f}, 8.f);
    LensStack stack;
    stack.add(makeFixedLens(layerMask(layersFrom(1)), a));
    stack.add(makeFixedLens(layerMask(layerBit(0) | layerBit(2)), b));
    const PolicyMap before = stack.compose(RayPolicy{}, kWidth, kHeight);
    stack.move(1, 0);
    const PolicyMap after = stack.compose(RayPolicy{}, kWidth, kHeight);
    const auto partial = [](float c) { return c > 0.f && c < 1.f; };
    const std::vector<uint8_t> crossing =
        maskWhere([&](int x, int y) { return partial(coverageAt(a, x, y)) && partial(coverageAt(b, x, y)); });
    ASSERT_GT(countOf(crossing), 0u);
    EXPECT_TRUE(sameMasks(crossing, changedPixels(before, after)));
}

TEST(PolicyMapDiff, ReorderingNonCommutingLensesChangesTheirOverlap) {
    glm::mat3 grey(0.f);
    for (int c = 0; c < 3; ++c) grey[c] = glm::vec3(1.f / 3.f);
    const glm::mat3 redOnly(glm::vec3(1.f, 0.f, 0.f), glm::vec3(0.f), glm::vec3(0.f));
    const LensRegion a = featheredEllipse({0.4f, 0.5f}, {0.5f, 0.7f}, 8.f);
    const LensRegion b = LensRegion::rectangle({0.6f, 0.5f}, {0.4f, 0.5f});
    LensStack stack;
    stack.add(makeFixedLens(colorMatrix(grey), a));
    stack.add(makeFixedLens(colorMatrix(redOnly), b));
    const PolicyMap before = stack.compose(RayPolicy{}, kWidth, kHeight);
    stack.move(1, 0);
    const PolicyMap after = stack.compose(RayPolicy{}, kWidth, kHeight);
    EXPECT_TRUE(sameMasks(maskWhere([&](int x, int y) { return coverageAt(a, x, y) > 0.f && coverageAt(b, x, y) > 0.f; }),
                          changedPixels(before, after)));
}

TEST(PolicyMapDiff, MarksOnlyInsideTheAreaAndKeepsEarlierMarks) {
    LensStack stack;
    auto lens = makeFixedLens(layerMask(layerBit(1)), featheredEllipse({0.5f, 0.5f}, {0.6f, 0.6f}, 4.f));
    stack.add(lens);
    const PolicyMap before = stack.compose(RayPolicy{}, kWidth, kHeight);
    lens->setContribution(layerMask(layerBit(3)));
    lens->commit();
    const PolicyMap after = stack.compose(RayPolicy{}, kWidth, kHeight);

    std::vector<uint8_t> changed(size_t(kWidth) * kHeight, 0);
    changed[0] = 1; // an earlier mark, outside the lens
    const PixelRect left{-20, -20, kWidth / 2, kHeight + 20}; // clipped to the view
    markChangedPixels(before, after, left, changed, 1);
    EXPECT_EQ(changed[0], 1);
    std::vector<uint8_t> all = changedPixels(before, after);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t i = size_t(y) * kWidth + size_t(x);
            if (i == 0) continue;
            ASSERT_EQ(changed[i], x < kWidth / 2 ? all[i] : 0) << x << "," << y;
        }
}

TEST(PolicyMapDiff, TheSameForAnyThreadCount) {
    LensStack stack;
    auto lens = makeFixedLens(layerMask(layerBit(1)), featheredEllipse({0.3f, 0.4f}, {0.4f, 0.5f}, 5.f));
    stack.add(lens);
    stack.add(makeFixedLens(colorMatrix(glm::mat3(0.5f)), featheredEllipse({0.5f, 0.5f}, {0.4f, 0.6f}, 7.f)));
    const PolicyMap before = stack.compose(RayPolicy{}, kWidth, kHeight);
    LensRegion moved = lens->region();
    moved.setCenter({0.35f, 0.45f});
    lens->setRegion(moved);
    lens->commit();
    const PolicyMap after = stack.compose(RayPolicy{}, kWidth, kHeight);
    const std::vector<uint8_t> one = changedPixels(before, after, 1);
    EXPECT_GT(countOf(one), 0u);
    EXPECT_EQ(one, changedPixels(before, after, 2));
    EXPECT_EQ(one, changedPixels(before, after, 5));
    EXPECT_EQ(one, changedPixels(before, after, 0));
}

TEST(PolicyMapDiff, PoliciesThatRenderAlikeAreTheSameWhicheverEntryAPixelUses) {
    // Two entries of one map may render alike (lens sets differ); a pixel moving between them
    // renders the same.
    PixelPolicy dim;
    dim.ray.color.matrix = glm::mat3(0.5f);
    PolicyMap before(4, 1), after(4, 1);
    const uint16_t first = before.addPolicy(dim);
    dim.lensSet = 0b10;
    const uint16_t second = before.addPolicy(dim);
    before.setPixel(0, 0, first);
    before.setPixel(1, 0, second);
    const uint16_t only = after.addPolicy(dim);
    after.setPixel(0, 0, only);
    after.setPixel(1, 0, only);
    after.setPixel(2, 0, only); // base before, dim after
    const std::vector<PolicyTerm> blend{{0, 0.25f}, {only, 0.75f}};
    after.setPixelBlend(3, 0, blend);
    std::vector<uint8_t> changed;
    markChangedPixels(before, after, {0, 0, 4, 1}, changed, 1);
    EXPECT_EQ(changed, (std::vector<uint8_t>{0, 0, 1, 1}));
}

TEST(PolicyMapDiff, RejectsMapsOfDifferentSizes) {
    std::vector<uint8_t> changed;
    EXPECT_THROW(markChangedPixels(PolicyMap(4, 4), PolicyMap(4, 5), {0, 0, 4, 4}, changed, 1), Error);
}
