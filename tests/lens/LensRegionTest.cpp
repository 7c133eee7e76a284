#include <mvcl/lens/LensRegion.h>

#include <mvcl/core/Error.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <span>
#include <vector>

using namespace mvcl;

namespace {

glm::vec2 pixelCentre(int x, int y) { return {float(x) + 0.5f, float(y) + 0.5f}; }

// Every pixel with coverage > 0 must lie inside pixelBounds; checked over the whole image.
void expectBoundsHoldEveryCoveredPixel(const LensRegion &region, int width, int height) {
    const PixelRect bounds = region.pixelBounds(width, height);
    EXPECT_GE(bounds.x0, 0);
    EXPECT_GE(bounds.y0, 0);
    EXPECT_LE(bounds.x1, width);
    EXPECT_LE(bounds.y1, height);
    int covered = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // rowSpan, the fast path of LensStack::compose, must agree with coverage().
            const LensRegion::RowSpan span = region.rowSpan(y, width, height);
            const float coverage = region.coverage(pixelCentre(x, y), width, height);
            if (x >= span.innerX0 && x < span.innerX1) {
                ASSERT_EQ(coverage, 1.f) << x << "," << y;
            }
            if (coverage > 0.f) {
                ASSERT_TRUE(x >= span.x0 && x < span.x1) << x << "," << y;
            }
            if (coverage <= 0.f) continue;
            ++covered;
            ASSERT_TRUE(x >= bounds.x0 && x < bounds.x1 && y >= bounds.y0 && y < bounds.y1)
                << "pixel " << x << "," << y << " outside bounds " << bounds.x0 << ".." << bounds.x1
                << " x " << bounds.y0 << ".." << bounds.y1 << " in " << width << "x" << height;
        }
    // Bounds are tight up to the 1-pixel margin (plus the outline): no more than a thin frame
    // around what is covered.
    if (covered > 0 && region.outlineWidth() == 0.f) {
        const glm::vec2 size = region.size() * glm::vec2(float(width), float(height));
        EXPECT_LE(bounds.x1 - bounds.x0, int(std::ceil(size.x)) + 3);
        EXPECT_LE(bounds.y1 - bounds.y0, int(std::ceil(size.y)) + 3);
    }
}

std::vector<glm::vec2> reversed(std::vector<glm::vec2> points) {
    return {points.rbegin(), points.rend()};
}

} // namespace

TEST(LensRegion, DefaultIsACentredHalfSizeRectangle) {
    const LensRegion region;
    EXPECT_EQ(region.shape(), LensRegion::Shape::Rectangle);
    EXPECT_EQ(region.center(), glm::vec2(0.5f));
    EXPECT_EQ(region.size(), glm::vec2(0.5f));
    EXPECT_EQ(region.coverage(pixelCentre(50, 50), 100, 100), 1.f);
    EXPECT_EQ(region.coverage(pixelCentre(10, 50), 100, 100), 0.f);
    EXPECT_NO_THROW(region.validate());
}

TEST(LensRegion, RectangleHardEdgeCoversPixelCentresInside) {
    // Spans x in [20, 60) px and y in [10, 30) px of a 100 x 50 image.
    const LensRegion region = LensRegion::rectangle({0.4f, 0.4f}, {0.4f, 0.4f});
    const int width = 100, height = 50;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const bool inside = x >= 20 && x < 60 && y >= 10 && y < 30;
            ASSERT_EQ(region.coverage(pixelCentre(x, y), width, height), inside ? 1.f : 0.f)
                << x << "," << y;
        }
    // Exactly on the edge counts as inside for a hard edge.
    EXPECT_EQ(region.signedDistance({20.f, 20.f}, width, height), 0.f);
    EXPECT_EQ(region.coverage({20.f, 20.f}, width, height), 1.f);
}

TEST(LensRegion, RectangleSignedDistanceIsExactInPixels) {
    const LensRegion region = LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f}); // [50,150]x[25,75]
    const int width = 200, height = 100;
    EXPECT_FLOAT_EQ(region.signedDistance({100.f, 50.f}, width, height), 25.f);
    EXPECT_FLOAT_EQ(region.signedDistance({60.f, 50.f}, width, height), 10.f);
    EXPECT_FLOAT_EQ(region.signedDistance({40.f, 50.f}, width, height), -10.f);
    EXPECT_FLOAT_EQ(region.signedDistance({100.f, 85.f}, width, height), -10.f);
    // Beyond a corner: Euclidean distance to the corner (150, 75).
    EXPECT_FLOAT_EQ(region.signedDistance({153.f, 79.f}, width, height), -5.f);
}

TEST(LensRegion, EllipseDistanceIsEuclideanInPixels) {
    const int width = 400, height = 200;
    const glm::vec2 centre(200.f, 100.f);
    // Semi-axes in pixels: a circle on a non-square image, a 4:1 and a 20:1 ellipse.
    for (const glm::vec2 &radii : {glm::vec2(50.f), glm::vec2(100.f, 25.f), glm::vec2(150.f, 7.5f)}) {
        const LensRegion region = LensRegion::ellipse(
            {0.5f, 0.5f}, {2.f * radii.x / float(width), 2.f * radii.y / float(height)});
        // Reference: distance to a dense sampling of the boundary.
        std::vector<glm::vec2> boundary;
        for (int i = 0; i < 20000; ++i) {
            const float angle = 6.28318531f * float(i) / 20000.f;
            boundary.push_back(centre + radii * glm::vec2(std::cos(angle), std::sin(angle)));
        }
        for (int y = 0; y < height; y += 11)
            for (int x = 0; x < width; x += 11) {
                const glm::vec2 p = pixelCentre(x, y);
                float nearest = std::numeric_limits<float>::infinity();
                for (const glm::vec2 &b : boundary) nearest = std::min(nearest, glm::length(p - b));
                const glm::vec2 q = (p - centre) / radii;
                const float expected = glm::dot(q, q) <= 1.f ? nearest : -nearest;
                ASSERT_NEAR(region.signedDistance(p, width, height), expected, 0.02f)
                    << "at " << p.x << "," << p.y << " radii " << radii.x << "," << radii.y;
            }
        EXPECT_NEAR(region.signedDistance(centre, width, height), radii.y, 1e-3f);
        EXPECT_NEAR(region.signedDistance(centre + glm::vec2(radii.x + 20.f, 0.f), width, height),
                    -20.f, 1e-3f);
        EXPECT_NEAR(region.signedDistance(centre - glm::vec2(0.f, radii.y + 3.f), width, height),
                    -3.f, 1e-3f);
    }
}

TEST(LensRegion, EllipseCoverageMatchesTheImplicitEquation) {
    const int width = 160, height = 90;
    const LensRegion region = LensRegion::ellipse({0.45f, 0.55f}, {0.6f, 0.3f});
    const glm::vec2 centre(0.45f * width, 0.55f * height);
    const glm::vec2 radii(0.3f * width, 0.15f * height);
    int inside = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec2 q = (pixelCentre(x, y) - centre) / radii;
            const float implicit = q.x * q.x + q.y * q.y;
            if (std::abs(implicit - 1.f) < 1e-3f) continue; // too close to call in float
            const bool expected = implicit < 1.f;
            inside += expected;
            ASSERT_EQ(region.coverage(pixelCentre(x, y), width, height), expected ? 1.f : 0.f)
                << x << "," << y;
        }
    // Area check: π·a·b pixels, within a boundary's worth.
    const float area = 3.14159265f * radii.x * radii.y;
    EXPECT_NEAR(float(inside), area, 2.f * (radii.x + radii.y) * 3.14159265f * 0.5f);
}

TEST(LensRegion, PolygonCoverageIgnoresWindingAndUsesEvenOdd) {
    const int width = 64, height = 64;
    // A right triangle with corners (0.25,0.25), (0.75,0.25), (0.25,0.75).
    const std::vector<glm::vec2> triangle{{0.25f, 0.25f}, {0.75f, 0.25f}, {0.25f, 0.75f}};
    const LensRegion clockwise = LensRegion::polygon(triangle);
    const LensRegion counter = LensRegion::polygon(reversed(triangle));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec2 p = pixelCentre(x, y);
            if (p.x + p.y == 64.f) continue; // exactly on the hypotenuse
            const bool inside = p.x > 16.f && p.y > 16.f && p.x + p.y < 64.f;
            ASSERT_EQ(clockwise.coverage(p, width, height), inside ? 1.f : 0.f) << x << "," << y;
            ASSERT_EQ(counter.signedDistance(p, width, height),
                      clockwise.signedDistance(p, width, height));
        }
    // A pentagram's centre is crossed twice: even-odd leaves it outside, its points inside.
    std::vector<glm::vec2> star;
    for (int i = 0; i < 5; ++i) {
        const float angle = -1.5707963f + float(i * 2) * 6.2831853f / 5.f;
        star.push_back(glm::vec2(0.5f) + 0.4f * glm::vec2(std::cos(angle), std::sin(angle)));
    }
    const LensRegion pentagram = LensRegion::polygon(star);
    EXPECT_EQ(pentagram.coverage({32.f, 32.f}, width, height), 0.f);
    EXPECT_EQ(pentagram.coverage({32.f, 0.1f * 64 + 4.f}, width, height), 1.f); // top point
}

TEST(LensRegion, PolygonSignedDistanceIsDistanceToNearestEdge) {
    const LensRegion square =
        LensRegion::polygon({{0.25f, 0.25f}, {0.75f, 0.25f}, {0.75f, 0.75f}, {0.25f, 0.75f}});
    const LensRegion same = LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f});
    for (const glm::vec2 &p : {glm::vec2(50.f, 40.f), glm::vec2(10.f, 10.f), glm::vec2(90.f, 20.f),
                               glm::vec2(27.f, 70.f), glm::vec2(200.f, 40.f)})
        EXPECT_NEAR(square.signedDistance(p, 100, 80), same.signedDistance(p, 100, 80), 1e-4f)
            << p.x << "," << p.y;
}

TEST(LensRegion, FeatherRampIsMonotoneAndWithinZeroOne) {
    const int width = 300, height = 120;
    for (const LensRegion &shape :
         {LensRegion::rectangle({0.5f, 0.5f}, {0.6f, 0.6f}), LensRegion::ellipse({0.5f, 0.5f}, {0.6f, 0.6f}),
          LensRegion::polygon({{0.2f, 0.2f}, {0.8f, 0.3f}, {0.5f, 0.8f}})}) {
        LensRegion region = shape;
        region.setFeather(12.f);
        // Walk from outside the left edge to the centre along the middle row.
        float previous = 0.f;
        bool reachedOne = false, sawRamp = false;
        for (float x = 0.f; x <= 150.f; x += 0.25f) {
            const float c = region.coverage({x, 60.f}, width, height);
            ASSERT_GE(c, 0.f);
            ASSERT_LE(c, 1.f);
            ASSERT_GE(c, previous) << "at x = " << x;
            sawRamp |= c > 0.f && c < 1.f;
            reachedOne |= c == 1.f;
            previous = c;
        }
        EXPECT_TRUE(sawRamp);
        EXPECT_TRUE(reachedOne);
    }
    LensRegion rectangle = LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f}); // left edge x = 75
    rectangle.setFeather(10.f);
    EXPECT_EQ(rectangle.coverage({75.f, 60.f}, width, height), 0.f);
    EXPECT_NEAR(rectangle.coverage({80.f, 60.f}, width, height), 0.5f, 1e-5f);
    EXPECT_EQ(rectangle.coverage({85.f, 60.f}, width, height), 1.f);
    EXPECT_EQ(rectangle.coverage({74.f, 60.f}, width, height), 0.f);
}

TEST(LensRegion, PixelBoundsContainEveryCoveredPixel) {
    const std::vector<std::pair<int, int>> sizes{{64, 64}, {200, 50}, {37, 113}, {1, 1}, {7, 3}};
    std::vector<LensRegion> regions{
        LensRegion::rectangle({0.5f, 0.5f}, {0.3f, 0.4f}),
        LensRegion::rectangle({0.05f, 0.95f}, {0.3f, 0.4f}), // clipped by the image corner
        LensRegion::ellipse({0.3f, 0.6f}, {0.5f, 0.2f}),
        LensRegion::ellipse({1.1f, 0.5f}, {0.5f, 0.5f}),    // mostly off screen
        LensRegion::ellipse({3.f, 3.f}, {0.5f, 0.5f}),      // entirely off screen
        LensRegion::polygon({{0.1f, 0.1f}, {0.9f, 0.2f}, {0.4f, 0.9f}, {0.3f, 0.4f}}),
        LensRegion::rectangle({0.5f, 0.5f}, {2.f, 2.f}),     // covers everything
    };
    const size_t plainCount = regions.size();
    for (size_t i = 0; i < plainCount; ++i) {
        LensRegion feathered = regions[i];
        feathered.setFeather(3.f);
        feathered.setOutlineWidth(4.f);
        regions.push_back(feathered);
    }
    for (const auto &[width, height] : sizes)
        for (const LensRegion &region : regions) expectBoundsHoldEveryCoveredPixel(region, width, height);
    EXPECT_TRUE(LensRegion::ellipse({3.f, 3.f}, {0.5f, 0.5f}).pixelBounds(64, 64).isEmpty());
}

TEST(LensRegion, RowSpansLeaveOnlyTheEdgeToPerPixelCoverage) {
    // The fast path must actually be taken: a large feathered ellipse or rectangle leaves only
    // a thin band per row to coverage().
    for (LensRegion region : {LensRegion::ellipse({0.5f, 0.5f}, {0.6f, 0.8f}),
                              LensRegion::rectangle({0.5f, 0.5f}, {0.6f, 0.8f})}) {
        region.setFeather(4.f);
        const LensRegion::RowSpan span = region.rowSpan(100, 200, 200);
        EXPECT_GT(span.innerX1 - span.innerX0, (span.x1 - span.x0) - 2 * (4 + 4)) << int(region.shape());
    }
}

TEST(LensRegion, PixelBoundsGrowWithTheOutline) {
    LensRegion region = LensRegion::rectangle({0.5f, 0.5f}, {0.2f, 0.2f}); // [40, 60) of 100
    const PixelRect plain = region.pixelBounds(100, 100);
    EXPECT_LE(plain.x0, 40);
    EXPECT_GE(plain.x1, 60);
    region.setOutlineWidth(10.f);
    const PixelRect outlined = region.pixelBounds(100, 100);
    EXPECT_LE(outlined.x0, 35);
    EXPECT_GE(outlined.x1, 65);
    EXPECT_LE(outlined.x0, plain.x0 - 5);
}

TEST(LensRegion, AspectRatioIsHonouredInPixels) {
    // A square in normalised coordinates is a 2:1 rectangle on a 2:1 image.
    const LensRegion region = LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f});
    int covered = 0, columns = 0, rows = 0;
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 200; ++x) covered += region.coverage(pixelCentre(x, y), 200, 100) > 0.f;
    for (int x = 0; x < 200; ++x) columns += region.coverage(pixelCentre(x, 50), 200, 100) > 0.f;
    for (int y = 0; y < 100; ++y) rows += region.coverage(pixelCentre(100, y), 200, 100) > 0.f;
    EXPECT_EQ(covered, 100 * 50);
    EXPECT_EQ(columns, 100);
    EXPECT_EQ(rows, 50);
}

TEST(LensRegion, MovingAndResizing) {
    LensRegion rectangle = LensRegion::rectangle({0.2f, 0.3f}, {0.1f, 0.2f});
    rectangle.setCenter({0.6f, 0.7f});
    rectangle.setSize({0.3f, 0.1f});
    EXPECT_EQ(rectangle.center(), glm::vec2(0.6f, 0.7f));
    EXPECT_EQ(rectangle.size(), glm::vec2(0.3f, 0.1f));

    LensRegion polygon = LensRegion::polygon({{0.1f, 0.1f}, {0.3f, 0.1f}, {0.2f, 0.5f}});
    EXPECT_NEAR(polygon.center().x, 0.2f, 1e-6f);
    EXPECT_NEAR(polygon.center().y, 0.3f, 1e-6f);
    EXPECT_NEAR(polygon.size().x, 0.2f, 1e-6f);
    EXPECT_NEAR(polygon.size().y, 0.4f, 1e-6f);
    polygon.setCenter({0.5f, 0.5f});
    EXPECT_NEAR(polygon.points()[0].x, 0.4f, 1e-6f);
    EXPECT_NEAR(polygon.points()[0].y, 0.3f, 1e-6f);
    polygon.setSize({0.4f, 0.2f}); // x doubled, y halved about the centre (0.5, 0.5)
    EXPECT_NEAR(polygon.points()[0].x, 0.3f, 1e-6f);
    EXPECT_NEAR(polygon.points()[0].y, 0.4f, 1e-6f);
    EXPECT_NEAR(polygon.points()[2].y, 0.6f, 1e-6f);
    EXPECT_NEAR(polygon.center().x, 0.5f, 1e-6f);
    EXPECT_NEAR(polygon.size().x, 0.4f, 1e-6f);
    EXPECT_NEAR(polygon.size().y, 0.2f, 1e-6f);
}

TEST(LensRegion, ValidateRejectsBadRegions) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NO_THROW(LensRegion::ellipse({0.5f, 0.5f}, {0.1f, 0.1f}).validate());
    EXPECT_NO_THROW(LensRegion::rectangle({-2.f, 5.f}, {0.1f, 0.1f}).validate()); // off screen is fine
    EXPECT_THROW(LensRegion::rectangle({0.5f, 0.5f}, {-0.1f, 0.1f}).validate(), Error);
    EXPECT_THROW(LensRegion::ellipse({0.5f, 0.5f}, {0.1f, -0.1f}).validate(), Error);
    EXPECT_THROW(LensRegion::rectangle({nan, 0.5f}, {0.1f, 0.1f}).validate(), Error);
    EXPECT_THROW(LensRegion::rectangle({0.5f, 0.5f}, {INFINITY, 0.1f}).validate(), Error);
    EXPECT_THROW(LensRegion::polygon({{0.f, 0.f}, {1.f, 1.f}}).validate(), Error);
    EXPECT_THROW(LensRegion::polygon({{0.f, 0.f}, {1.f, 0.f}, {nan, 1.f}}).validate(), Error);
    LensRegion feathered;
    feathered.setFeather(-1.f);
    EXPECT_THROW(feathered.validate(), Error);
    LensRegion outlined;
    outlined.setOutlineWidth(nan);
    EXPECT_THROW(outlined.validate(), Error);
    try {
        LensRegion::polygon({}).validate();
        FAIL() << "expected an error";
    } catch (const Error &e) {
        EXPECT_EQ(e.source(), "lens region");
    }
}

TEST(LensRegion, ZeroSizeRegionsAreValidAndEmpty) {
    const std::vector<LensRegion> empties = {LensRegion::rectangle({0.5f, 0.5f}, {0.f, 0.1f}),
                                             LensRegion::ellipse({0.5f, 0.5f}, {0.f, 0.f}),
                                             LensRegion::polygon({{0.f, 0.5f}, {1.f, 0.5f}, {0.5f, 0.5f}})};
    for (LensRegion region : empties) {
        region.setFeather(3.f);
        EXPECT_NO_THROW(region.validate());
        EXPECT_TRUE(region.isEmpty());
        EXPECT_TRUE(region.pixelBounds(40, 30).isEmpty());
        EXPECT_EQ(region.coverage({20.f, 15.f}, 40, 30), 0.f);
        const LensRegion::RowSpan span = region.rowSpan(15, 40, 30);
        EXPECT_EQ(span.x0, span.x1);
    }
    EXPECT_FALSE(LensRegion::rectangle({0.5f, 0.5f}, {0.01f, 0.01f}).isEmpty());
}

TEST(LensRegion, DegenerateRegionsNeverProduceNaNCoverage) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const LensRegion &region :
         {LensRegion::polygon({}), LensRegion::ellipse({0.5f, 0.5f}, {0.f, 0.f}),
          LensRegion::rectangle({nan, 0.5f}, {0.1f, 0.1f}), LensRegion::polygon({{0.5f, 0.5f}})}) {
        LensRegion feathered = region;
        feathered.setFeather(2.f);
        for (const LensRegion &r : {region, feathered}) {
            const float c = r.coverage({10.5f, 10.5f}, 20, 20);
            EXPECT_TRUE(c == 0.f || c == 1.f) << c;
            (void)r.pixelBounds(20, 20);
        }
    }
}

namespace {

// Random regions drawn from the generator's raw output (every standard library draws the same).
float uniform(std::mt19937 &random, float lo, float hi) {
    return lo + (hi - lo) * float(random() >> 8) * (1.f / 16777216.f);
}

/// Ellipses of every kind the fast paths must get right: thin, tiny (under a pixel), huge, far
/// off screen, feathered wider than they are.
LensRegion randomEllipse(std::mt19937 &random) {
    const float scale = std::pow(10.f, uniform(random, -2.5f, 2.f));
    const glm::vec2 size{scale * uniform(random, 0.05f, 1.f), scale * uniform(random, 0.05f, 1.f)};
    const glm::vec2 center{uniform(random, -0.5f, 1.5f), uniform(random, -0.5f, 1.5f)};
    LensRegion region = LensRegion::ellipse(center, size);
    switch (random() % 4) {
    case 0: break;
    case 1: region.setFeather(uniform(random, 0.1f, 3.f)); break;
    case 2: region.setFeather(uniform(random, 3.f, 30.f)); break;
    default: region.setFeather(uniform(random, 30.f, 400.f)); break;
    }
    return region;
}

/// coverage() as the scalar code computes it from signedDistance(): what the 4-wide ellipse
/// kernel must reproduce bit for bit.
float scalarCoverage(const LensRegion &region, const glm::vec2 &pixel, int width, int height) {
    const glm::vec2 imageSize{float(width), float(height)};
    if (region.shape() == LensRegion::Shape::Ellipse) {
        const glm::vec2 radii = 0.5f * region.size() * imageSize;
        const glm::vec2 scaled = glm::abs(pixel - region.center() * imageSize) / radii;
        const float radiusSquared = glm::dot(scaled, scaled);
        if (!(radiusSquared <= 1.f)) return 0.f;
        if (!(region.feather() > 0.f)) return 1.f;
        if ((1.f - std::sqrt(radiusSquared)) * std::min(radii.x, radii.y) >= region.feather()) return 1.f;
    }
    const float distance = region.signedDistance(pixel, width, height);
    if (!(region.feather() > 0.f)) return distance >= 0.f ? 1.f : 0.f;
    if (!(distance > 0.f)) return 0.f;
    const float t = std::min(distance / region.feather(), 1.f);
    return t * t * (3.f - 2.f * t);
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

} // namespace

TEST(LensRegion, EllipseCoverageIsTheScalarComputationBitForBit) {
    std::mt19937 random(7);
    for (int round = 0; round < 400; ++round) {
        const LensRegion region = randomEllipse(random);
        const int width = 1 + int(random() % 400), height = 1 + int(random() % 300);
        const glm::vec2 c = region.center() * glm::vec2(float(width), float(height));
        const glm::vec2 half = 0.5f * region.size() * glm::vec2(float(width), float(height));
        for (int k = 0; k < 200; ++k) {
            // Points near the boundary, where the iteration runs, and anywhere.
            const float angle = uniform(random, 0.f, 6.2831853f);
            const float radius = k % 2 ? uniform(random, 0.9f, 1.1f) : uniform(random, 0.f, 1.5f);
            const glm::vec2 p = c + radius * half * glm::vec2(std::cos(angle), std::sin(angle));
            const float expected = scalarCoverage(region, p, width, height);
            const float actual = region.coverage(p, width, height);
            ASSERT_TRUE(sameBits(expected, actual)) << "round " << round << " at " << p.x << "," << p.y
                                                    << ": " << expected << " vs " << actual;
        }
    }
}

TEST(LensRegion, EdgeCoverageEqualsCoverageBitForBit) {
    std::mt19937 random(11);
    for (int round = 0; round < 300; ++round) {
        LensRegion region = randomEllipse(random);
        if (round % 4 == 1) {
            region = LensRegion::rectangle(region.center(), region.size());
            region.setFeather(uniform(random, 0.f, 12.f));
        } else if (round % 4 == 2) {
            region = LensRegion::polygon({{0.1f, 0.2f}, {0.8f, 0.1f}, {0.6f, 0.9f}, {0.3f, 0.5f}});
            region.setFeather(uniform(random, 0.f, 12.f));
        }
        const int width = 1 + int(random() % 300), height = 1 + int(random() % 200);
        std::vector<float> row(static_cast<size_t>(width));
        for (int y = 0; y < height; ++y) {
            const LensRegion::RowSpan span = region.rowSpan(y, width, height);
            std::fill(row.begin(), row.end(), -1.f);
            region.edgeCoverage(y, span, width, height, std::span(row).subspan(size_t(span.x0), size_t(span.x1 - span.x0)));
            for (int x = span.x0; x < span.x1; ++x) {
                const float value = row[size_t(x)];
                if (x >= span.innerX0 && x < span.innerX1) {
                    ASSERT_EQ(value, -1.f) << "the inner part is not written";
                } else {
                    ASSERT_TRUE(sameBits(value, region.coverage({float(x) + 0.5f, float(y) + 0.5f}, width, height)))
                        << "round " << round << " pixel " << x << "," << y;
                }
            }
        }
    }
}

TEST(LensRegion, RowSpansHoldForEllipsesOfAnySizeAndPlace) {
    // The span of an ellipse ends where the ellipse does (with a margin), not at its box.
    std::mt19937 random(3);
    for (int round = 0; round < 150; ++round)
        expectBoundsHoldEveryCoveredPixel(randomEllipse(random), 1 + int(random() % 200), 1 + int(random() % 150));
    for (const float scale : {1e3f, 1e5f}) // radii of 10⁵ and 10⁷ pixels, the edge on screen
        for (const float feather : {0.f, 5.f}) {
            LensRegion huge = LensRegion::ellipse({0.5f + 0.5f * scale, 0.5f}, {scale + 0.3f, 2.f * scale});
            huge.setFeather(feather);
            expectBoundsHoldEveryCoveredPixel(huge, 100, 100);
        }
    LensRegion ellipse = LensRegion::ellipse({0.5f, 0.5f}, {0.5f, 0.8f});
    ellipse.setFeather(4.f);
    const LensRegion::RowSpan nearTop = ellipse.rowSpan(25, 200, 200); // 5 rows below the top
    EXPECT_LT(nearTop.x1 - nearTop.x0, 45) << "the chord is 36 pixels, the box 100";
}
