// LensStack::compose against the pixel-by-pixel serial implementation it replaced
// (referenceCompose, kept here as it was): the same policies in the same order, and per pixel
// the same mix, terms and weights, bit for bit, over random stacks and image sizes and for
// several thread counts; where it fails, the same error.
#include <mvcl/lens/LensStack.h>

#include "lens/FixedLens.h"

#include <mvcl/core/Error.h>
#include <mvcl/lens/PolicyComposition.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

using namespace mvcl;
using test::makeFixedLens;

namespace {

// ---------------------------------------------------------------------------------------------
// The implementation before row-span segments and parallel bands, unchanged but for being a
// free function of the stack: one PixelCover per pixel of the row, then setPixel or
// setPixelBlend per pixel.

using Snapshots = std::vector<std::shared_ptr<const LensSnapshot>>;

PixelPolicy composeFromSnapshots(const Snapshots &snapshots, const RayPolicy &base, uint64_t lensSet) {
    PixelPolicy policy{base, glm::mat3(1.f), 0};
    for (uint64_t bits = lensSet; bits != 0; bits &= bits - 1) {
        const int index = std::countr_zero(bits);
        policy = applyContribution(policy, snapshots[size_t(index)]->contribution);
    }
    policy.lensSet = lensSet;
    return policy;
}

struct PixelCover {
    uint64_t fullSet = 0;
    int partialCount = 0;
    std::array<int, LensStack::kMaxBlendedLenses> partialLens{};
    std::array<float, LensStack::kMaxBlendedLenses> partialWeight{};
    bool touched = false;

    void add(int lens, float weight) {
        touched = true;
        if (weight >= 1.f) {
            fullSet |= uint64_t(1) << lens;
        } else if (weight > 0.f) {
            if (partialCount < LensStack::kMaxBlendedLenses) {
                partialLens[size_t(partialCount)] = lens;
                partialWeight[size_t(partialCount++)] = weight;
            } else if (weight >= 0.5f) {
                fullSet |= uint64_t(1) << lens; // past the exact blend: round to in or out
            }
        }
    }
};

PolicyMap referenceCompose(const LensStack &stack, const RayPolicy &base, int width, int height) {
    PolicyMap map(width, height, base);
    // One snapshot per lens for the whole frame: a commit from another thread cannot tear it.
    Snapshots snapshots;
    std::vector<int> active;
    std::vector<PixelRect> bounds;
    for (int i = 0; i < stack.size(); ++i) {
        snapshots.push_back(stack.lenses()[size_t(i)]->snapshot());
        const LensSnapshot &s = *snapshots.back();
        if (!s.enabled || s.contribution.isIdentity()) continue;
        const PixelRect r = s.region.pixelBounds(width, height);
        if (r.isEmpty()) continue;
        active.push_back(i);
        bounds.push_back(r);
    }
    if (active.empty()) return map;

    std::unordered_map<uint64_t, uint16_t> policyOfSet{{0, 0}};
    uint64_t lastSet = 0;
    uint16_t lastPolicy = 0;
    auto policyFor = [&](uint64_t set) {
        if (set == lastSet) return lastPolicy; // neighbouring pixels mostly share their set
        auto [it, inserted] = policyOfSet.try_emplace(set, 0);
        if (inserted) it->second = map.addPolicy(composeFromSnapshots(snapshots, base, set));
        lastSet = set;
        lastPolicy = it->second;
        return lastPolicy;
    };

    // Rows at a time: only pixels inside some lens's bounds are visited.
    std::vector<PixelCover> row(static_cast<size_t>(width));
    std::vector<PolicyTerm> terms;
    for (int y = 0; y < height; ++y) {
        int rowX0 = width, rowX1 = 0;
        for (size_t k = 0; k < active.size(); ++k) {
            const PixelRect &r = bounds[k];
            if (y < r.y0 || y >= r.y1) continue;
            const int lens = active[k];
            const LensRegion &region = snapshots[size_t(lens)]->region;
            const LensRegion::RowSpan span = region.rowSpan(y, width, height);
            auto addCoverage = [&](int x) {
                row[size_t(x)].add(lens, region.coverage({float(x) + 0.5f, float(y) + 0.5f}, width, height));
            };
            for (int x = span.x0; x < span.innerX0; ++x) addCoverage(x);
            for (int x = span.innerX0; x < span.innerX1; ++x) row[size_t(x)].add(lens, 1.f);
            for (int x = span.innerX1; x < span.x1; ++x) addCoverage(x);
            if (span.x0 < span.x1) {
                rowX0 = std::min(rowX0, span.x0);
                rowX1 = std::max(rowX1, span.x1);
            }
        }
        for (int x = rowX0; x < rowX1; ++x) {
            PixelCover &cover = row[size_t(x)];
            if (!cover.touched) continue;
            if (cover.partialCount == 0) {
                if (cover.fullSet != 0) map.setPixel(x, y, policyFor(cover.fullSet));
            } else {
                // Every subset of the partly covering lenses, weighted by the chance that
                // exactly those apply: an exact blend of the images with and without each.
                terms.clear();
                const int n = cover.partialCount;
                for (uint32_t subset = 0; subset < (1u << n); ++subset) {
                    uint64_t set = cover.fullSet;
                    float weight = 1.f;
                    for (int j = 0; j < n; ++j) {
                        const bool in = (subset >> j) & 1u;
                        if (in) set |= uint64_t(1) << cover.partialLens[size_t(j)];
                        weight *= in ? cover.partialWeight[size_t(j)] : 1.f - cover.partialWeight[size_t(j)];
                    }
                    terms.push_back({policyFor(set), weight});
                }
                map.setPixelBlend(x, y, terms);
            }
            cover = PixelCover{};
        }
    }
    return map;
}

// ---------------------------------------------------------------------------------------------
// Comparing maps exactly

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

::testing::AssertionResult identicalMaps(const PolicyMap &expected, const PolicyMap &actual) {
    if (expected.width() != actual.width() || expected.height() != actual.height())
        return ::testing::AssertionFailure() << "sizes differ";
    if (expected.policies().size() != actual.policies().size())
        return ::testing::AssertionFailure() << expected.policies().size() << " policies expected, got "
                                             << actual.policies().size();
    for (size_t i = 0; i < expected.policies().size(); ++i) {
        const PixelPolicy &e = expected.policies()[i], &a = actual.policies()[i];
        if (!e.rendersLike(a) || e.lensSet != a.lensSet)
            return ::testing::AssertionFailure() << "policy " << i << " differs (lens sets " << e.lensSet << ", "
                                                 << a.lensSet << ")";
    }
    if (expected.mixCount() != actual.mixCount())
        return ::testing::AssertionFailure() << expected.mixCount() << " mixes expected, got " << actual.mixCount();
    for (int y = 0; y < expected.height(); ++y)
        for (int x = 0; x < expected.width(); ++x) {
            if (expected.mixIndex(x, y) != actual.mixIndex(x, y))
                return ::testing::AssertionFailure() << "pixel (" << x << ", " << y << "): mix "
                                                     << expected.mixIndex(x, y) << " expected, got "
                                                     << actual.mixIndex(x, y);
            const auto te = expected.terms(x, y), ta = actual.terms(x, y);
            if (te.size() != ta.size())
                return ::testing::AssertionFailure() << "pixel (" << x << ", " << y << "): " << te.size()
                                                     << " terms expected, got " << ta.size();
            for (size_t i = 0; i < te.size(); ++i)
                if (te[i].policy != ta[i].policy || !sameBits(te[i].weight, ta[i].weight))
                    return ::testing::AssertionFailure()
                           << "pixel (" << x << ", " << y << ") term " << i << ": policy " << te[i].policy
                           << " weight " << te[i].weight << " expected, got " << ta[i].policy << " weight "
                           << ta[i].weight;
        }
    return ::testing::AssertionSuccess();
}

/// compose() with each thread count equals referenceCompose, or both throw the same error.
void expectComposeMatchesReference(const LensStack &stack, const RayPolicy &base, int width, int height,
                                   const std::string &what) {
    std::optional<PolicyMap> expected;
    std::string expectedError;
    try {
        expected.emplace(referenceCompose(stack, base, width, height));
    } catch (const Error &e) {
        expectedError = e.what();
    }
    for (const int threads : {1, 2, 5}) {
        SCOPED_TRACE(what + ", " + std::to_string(width) + "x" + std::to_string(height) + ", threads " +
                     std::to_string(threads));
        try {
            const PolicyMap actual = stack.compose(base, width, height, threads);
            ASSERT_TRUE(expected.has_value()) << "compose did not throw '" << expectedError << "'";
            ASSERT_TRUE(identicalMaps(*expected, actual));
        } catch (const Error &e) {
            ASSERT_FALSE(expected.has_value()) << "compose threw '" << e.what() << "'";
            EXPECT_EQ(expectedError, e.what());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Random stacks. Values come from the generator's raw output, not from std distributions, so
// every standard library draws the same stacks.

using Random = std::mt19937;

float uniform(Random &random, float lo, float hi) {
    return lo + (hi - lo) * float(random() >> 8) * (1.f / 16777216.f);
}
int uniformInt(Random &random, int lo, int hi) { return lo + int(random() % uint32_t(hi - lo + 1)); }
bool chance(Random &random, int percent) { return int(random() % 100) < percent; }

LensContribution randomContribution(Random &random) {
    LensContribution c;
    switch (random() % 6) {
    case 0: c.visibility[size_t(RayType::Primary)].layerMask = uint32_t(random()) | 1u; break;
    case 1: c.visibility[size_t(RayType::Primary)].tMin = uniform(random, 0.f, 3.f) + 0.01f; break;
    case 2: c.color.matrix = glm::mat3(uniform(random, 0.1f, 2.f)); break;
    case 3: c.shading.shadows = chance(random, 50); break;
    case 4: {
        const glm::vec3 center(uniform(random, -1.f, 1.f), 0.f, 0.f);
        float radius = uniform(random, 0.1f, 1.f);
        RayQuery &query = c.visibility[size_t(RayType::Shadow)];
        // One to three volumes: enough of these lenses over one pixel exceed kMaxClipVolumes.
        const int count = uniformInt(random, 1, 3);
        for (int i = 0; i < count; ++i) {
            query.addClip(ClipVolume::sphere(center, radius, ClipVolume::Keep::Outside));
            radius += 1.f;
        }
        break;
    }
    default: {
        const float m = uniform(random, 1.f, 4.f);
        c.sampleFromScreen = glm::mat3(glm::vec3(1.f / m, 0.f, 0.f), glm::vec3(0.f, 1.f / m, 0.f),
                                       glm::vec3(0.5f - 0.5f / m, 0.5f - 0.5f / m, 1.f));
        break;
    }
    }
    if (chance(random, 5)) c = LensContribution{}; // changes nothing: compose skips the lens
    return c;
}

/// Scattered regions may lie partly off screen and exceed it, so that the border cuts them;
/// clustered ones pile up around the centre with wide feathers, so that more than
/// kMaxBlendedLenses edges meet.
LensRegion randomRegion(Random &random, bool clustered) {
    const glm::vec2 center = clustered ? glm::vec2{uniform(random, 0.4f, 0.6f), uniform(random, 0.4f, 0.6f)}
                                       : glm::vec2{uniform(random, -0.3f, 1.3f), uniform(random, -0.3f, 1.3f)};
    const glm::vec2 size = clustered ? glm::vec2{uniform(random, 0.2f, 0.6f), uniform(random, 0.2f, 0.6f)}
                                     : glm::vec2{uniform(random, 0.02f, 1.2f), uniform(random, 0.02f, 1.2f)};
    LensRegion region;
    switch (random() % 3) {
    case 0: region = LensRegion::rectangle(center, size); break;
    case 1: region = LensRegion::ellipse(center, size); break;
    default: {
        std::vector<glm::vec2> points(size_t(uniformInt(random, 3, 7)));
        for (glm::vec2 &p : points)
            p = center + glm::vec2(uniform(random, -0.5f, 0.5f) * size.x, uniform(random, -0.5f, 0.5f) * size.y);
        region = LensRegion::polygon(std::move(points));
        break;
    }
    }
    switch (clustered ? 2 : random() % 4) {
    case 0: region.setFeather(0.f); break;
    case 1: region.setFeather(uniform(random, 0.5f, 4.f)); break;
    case 2: region.setFeather(uniform(random, 4.f, 40.f)); break;
    default: region.setFeather(float(uniformInt(random, 1, 12))); break;
    }
    if (chance(random, 10)) region.setOutlineWidth(uniform(random, 1.f, 30.f));
    return region;
}

LensStack randomStack(Random &random) {
    LensStack stack;
    const bool many = chance(random, 20);
    const int count = many ? uniformInt(random, 6, 12) : uniformInt(random, 1, 5);
    for (int i = 0; i < count; ++i) {
        LensRegion region = randomRegion(random, many && chance(random, 70));
        if (region.shape() == LensRegion::Shape::Polygon) {
            try {
                region.validate();
            } catch (const Error &) {
                region = LensRegion::ellipse(region.center(), {0.3f, 0.3f}); // a flat polygon
            }
        }
        auto lens = makeFixedLens(randomContribution(random), region);
        if (chance(random, 10)) {
            lens->setEnabled(false);
            lens->commit();
        }
        stack.add(lens);
    }
    return stack;
}

std::pair<int, int> randomSize(Random &random, int round) {
    if (round % 25 == 0) return {1280, 720};
    switch (random() % 5) {
    case 0: return {uniformInt(random, 1, 3), uniformInt(random, 1, 3)};
    case 1: return {1, uniformInt(random, 1, 200)};
    case 2: return {uniformInt(random, 1, 200), 1};
    default: return {uniformInt(random, 2, 320), uniformInt(random, 2, 240)};
    }
}

} // namespace

TEST(LensStackCompose, EqualsTheSerialPixelByPixelComposeOnRandomStacks) {
    Random random(20240611);
    for (int round = 0; round < 500; ++round) {
        const LensStack stack = randomStack(random);
        const auto [width, height] = randomSize(random, round);
        RayPolicy base;
        base.shading.maxDepth = round % 5;
        expectComposeMatchesReference(stack, base, width, height, "round " + std::to_string(round));
        if (::testing::Test::HasFatalFailure()) return;
    }
}

TEST(LensStackCompose, EqualsTheSerialComposeWhereMoreThanFourFeatheredEdgesMeet) {
    // Six wide feathers over the same spot: past kMaxBlendedLenses the upper partial lenses
    // are rounded, in stack order.
    LensStack stack;
    for (int i = 0; i < 6; ++i) {
        LensRegion region = (i % 2 ? LensRegion::ellipse({0.5f + 0.01f * float(i), 0.5f}, {0.5f, 0.6f})
                                   : LensRegion::rectangle({0.5f, 0.5f - 0.01f * float(i)}, {0.4f, 0.5f}));
        region.setFeather(60.f);
        LensContribution c;
        c.visibility[size_t(RayType::Primary)].layerMask = ~(1u << i);
        stack.add(makeFixedLens(c, region));
    }
    const PolicyMap map = stack.compose(RayPolicy{}, 400, 300, 2);
    size_t mostTerms = 0;
    for (int y = 0; y < 300; ++y)
        for (int x = 0; x < 400; ++x) mostTerms = std::max(mostTerms, map.terms(x, y).size());
    EXPECT_EQ(mostTerms, size_t(1) << LensStack::kMaxBlendedLenses);
    expectComposeMatchesReference(stack, RayPolicy{}, 400, 300, "six feathers");
}

TEST(LensStackCompose, EqualsTheSerialComposeForTheBenchmarkStack) {
    // The shape of mvcl-lens-bench's stacks: ellipses around the centre, feather 4 px.
    LensStack stack;
    for (int i = 0; i < 8; ++i) {
        const float angle = 0.785f * float(i);
        LensRegion region = LensRegion::ellipse({0.5f + 0.08f * std::cos(angle), 0.5f + 0.08f * std::sin(angle)},
                                                {0.45f, 0.6f});
        region.setFeather(4.f);
        LensContribution c;
        c.visibility[size_t(RayType::Primary)].layerMask = ~(1u << i);
        stack.add(makeFixedLens(c, region));
        if (i == 0 || i == 2 || i == 7) expectComposeMatchesReference(stack, RayPolicy{}, 1280, 720, "bench");
    }
}

TEST(LensStackCompose, ZeroThreadsMeansAllCoresAndGivesTheSameMap) {
    LensRegion region = LensRegion::ellipse({0.4f, 0.5f}, {0.5f, 0.5f});
    region.setFeather(6.f);
    LensStack stack;
    LensContribution c;
    c.color.matrix = glm::mat3(0.5f);
    stack.add(makeFixedLens(c, region));
    region.setCenter({0.6f, 0.5f});
    stack.add(makeFixedLens(c, region));
    EXPECT_TRUE(identicalMaps(referenceCompose(stack, RayPolicy{}, 300, 200), stack.compose(RayPolicy{}, 300, 200)));
    EXPECT_TRUE(identicalMaps(referenceCompose(stack, RayPolicy{}, 300, 200), stack.compose(RayPolicy{}, 300, 200, 0)));
}

TEST(LensStackCompose, TooManyClipVolumesAreReportedNotThrown) {
    // Four lenses with three volumes each: where three or more overlap, the set needs more than
    // kMaxClipVolumes on shadow rays. Compose (the render path) does not throw; the map counts
    // what it left out, and checkClipVolumes turns that into an error for tools.
    LensStack stack;
    for (int i = 0; i < 4; ++i) {
        LensContribution c;
        RayQuery &query = c.visibility[size_t(RayType::Shadow)];
        for (int k = 0; k < 3; ++k)
            query.addClip(ClipVolume::sphere(glm::vec3(0.f), float(1 + 3 * i + k), ClipVolume::Keep::Outside));
        stack.add(makeFixedLens(c, LensRegion::ellipse({0.3f + 0.12f * float(i), 0.5f}, {0.5f, 0.5f})));
    }
    PolicyMap map(1, 1);
    EXPECT_NO_THROW(map = stack.compose(RayPolicy{}, 200, 100, 2));
    EXPECT_GT(map.droppedClipVolumes(), 0);
    EXPECT_EQ(stack.compose(RayPolicy{}, 200, 100, 1).droppedClipVolumes(), map.droppedClipVolumes());
    EXPECT_THROW(LensStack::checkClipVolumes(map), Error);
    stack.remove(3);
    stack.remove(2);
    const PolicyMap fits = stack.compose(RayPolicy{}, 200, 100, 2);
    EXPECT_EQ(fits.droppedClipVolumes(), 0);
    EXPECT_NO_THROW(LensStack::checkClipVolumes(fits));
}
