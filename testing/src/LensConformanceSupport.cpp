// Random values, comparisons and rendering for the lens conformance checks: see
// LensConformanceSupport.h.

#include <mvcl/testing/LensConformanceSupport.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

namespace mvcl::test {

namespace {

double uniformReal(Random &random, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random);
}

/// A finite interval to draw from inside a declared (possibly unbounded) range.
std::pair<double, double> drawableRange(const PropertyDecl &decl) {
    double lo = decl.minimum, hi = decl.maximum;
    if (!std::isfinite(lo) && !std::isfinite(hi)) return {-100.0, 100.0};
    if (!std::isfinite(lo)) lo = hi - 10.0 * (1.0 + std::abs(hi));
    if (!std::isfinite(hi)) hi = lo + 10.0 * (1.0 + std::abs(lo));
    return {lo, hi};
}

} // namespace

PropertyValue randomValidValue(const PropertyDecl &decl, Random &random) {
    switch (decl.type) {
    case PropertyType::Bool:
        return PropertyValue::boolean(random() % 2 == 1);
    case PropertyType::Int: {
        auto [lo, hi] = drawableRange(decl);
        lo = std::max(lo, -1e6);
        hi = std::min(hi, 1e6);
        return PropertyValue::integer(std::uniform_int_distribution<int>(
            int(std::ceil(lo)), int(std::floor(hi)))(random));
    }
    case PropertyType::Real: {
        const auto [lo, hi] = drawableRange(decl);
        return PropertyValue::real(uniformReal(random, lo, hi));
    }
    case PropertyType::Color: {
        const double lo = std::max(0.0, std::isfinite(decl.minimum) ? decl.minimum : 0.0);
        const double hi = std::min(2.0, std::isfinite(decl.maximum) ? decl.maximum : 2.0);
        return PropertyValue::color({float(uniformReal(random, lo, hi)),
                                     float(uniformReal(random, lo, hi)),
                                     float(uniformReal(random, lo, hi))});
    }
    case PropertyType::Choice:
        return PropertyValue::choice(decl.choices.at(random() % decl.choices.size()));
    case PropertyType::LayerSet:
        switch (random() % 3) {
        case 0: return PropertyValue::layerSet(layersFrom(int(random() % 5)));
        case 1: return PropertyValue::layerSet(uint32_t(random() % 16)); // the scenes' layers
        default: return PropertyValue::layerSet(uint32_t(random()));
        }
    case PropertyType::RayTypeSet:
        return PropertyValue::rayTypeSet(uint8_t(random() % 16));
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3: {
        // Within the scenes' few units, so that random points and boxes meet the geometry.
        const double lo = std::max(decl.minimum, -3.0), hi = std::min(decl.maximum, 3.0);
        const glm::dvec3 a{uniformReal(random, lo, hi), uniformReal(random, lo, hi), uniformReal(random, lo, hi)};
        if (decl.type == PropertyType::Point3) return PropertyValue::point3(a);
        if (decl.type == PropertyType::Vector3) return PropertyValue::vector3(a);
        const glm::dvec3 b{uniformReal(random, lo, hi), uniformReal(random, lo, hi), uniformReal(random, lo, hi)};
        return PropertyValue::box3({glm::min(a, b), glm::max(a, b)});
    }
    case PropertyType::Transform: {
        glm::dmat4 m(1.0);
        const double angle = uniformReal(random, -3.0, 3.0), scale = uniformReal(random, 0.5, 2.0);
        m[0] = glm::dvec4(scale * std::cos(angle), scale * std::sin(angle), 0.0, 0.0);
        m[1] = glm::dvec4(-scale * std::sin(angle), scale * std::cos(angle), 0.0, 0.0);
        m[3] = glm::dvec4(uniformReal(random, -2.0, 2.0), uniformReal(random, -2.0, 2.0), uniformReal(random, -2.0, 2.0), 1.0);
        return PropertyValue::transform(m);
    }
    }
    return decl.defaultValue;
}

void randomizeProperties(Lens &lens, Random &random) {
    for (const PropertyDecl &decl : lens.properties())
        lens.setProperty(decl.name, randomValidValue(decl, random));
    lens.commit();
}

LensRegion randomCentralRegion(Random &random, float featherPixels) {
    const glm::vec2 center{float(uniformReal(random, 0.4, 0.6)), float(uniformReal(random, 0.4, 0.6))};
    const glm::vec2 size{float(uniformReal(random, 0.4, 0.7)), float(uniformReal(random, 0.4, 0.7))};
    LensRegion region = random() % 2 ? LensRegion::ellipse(center, size)
                                     : LensRegion::rectangle(center, size);
    region.setFeather(featherPixels);
    return region;
}

std::shared_ptr<Lens> randomLens(const LensFactory &create, Random &random, float featherPixels) {
    std::shared_ptr<Lens> lens = create();
    randomizeProperties(*lens, random);
    lens->setRegion(randomCentralRegion(random, featherPixels));
    lens->commit();
    return lens;
}

std::string describeValues(const Lens &lens) {
    std::ostringstream out;
    const PropertyTable &table = lens.properties();
    const std::vector<PropertyValue> values = lens.committedValues();
    for (std::size_t i = 0; i < table.size() && i < values.size(); ++i)
        out << (i ? " " : "") << table[i].name << "=" << values[i].toString();
    return lens.typeName() + "{" + out.str() + "}";
}

// ---------------------------------------------------------------------------------------------
// Comparing policies and images

std::string describePolicy(const PixelPolicy &p) {
    std::ostringstream out;
    for (int t = 0; t < kRayTypeCount; ++t) {
        const RayQuery &q = p.ray.visibility[t];
        out << "vis" << t << "{layers=" << std::hex << q.layerMask << std::dec << " t=[" << q.tMin
            << "," << q.tMax << "] clips=" << q.clipCount() << "} ";
    }
    const ShadingPolicy &s = p.ray.shading;
    out << "shading{shadows=" << s.shadows << " strength=" << s.shadowStrength << " tint="
        << s.shadowTint.x << "," << s.shadowTint.y << "," << s.shadowTint.z << " refl="
        << s.reflections << " refr=" << s.refractions << " depth=" << s.maxDepth << "} color{";
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) out << p.ray.color.matrix[c][r] << (c == 2 && r == 2 ? "" : ",");
    out << " + " << p.ray.color.offset.x << "," << p.ray.color.offset.y << ","
        << p.ray.color.offset.z << "} shaping{";
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) out << p.sampleFromScreen[c][r] << (c == 2 && r == 2 ? "" : ",");
    out << "}";
    return out.str();
}

::testing::AssertionResult samePolicyMaps(const PolicyMap &a, const PolicyMap &b) {
    if (a.width() != b.width() || a.height() != b.height())
        return ::testing::AssertionFailure() << "policy maps differ in size";
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const auto ta = a.terms(x, y), tb = b.terms(x, y);
            bool same = ta.size() == tb.size();
            for (std::size_t i = 0; same && i < ta.size(); ++i)
                same = ta[i].weight == tb[i].weight &&
                       a.policy(ta[i].policy).rendersLike(b.policy(tb[i].policy));
            if (!same)
                return ::testing::AssertionFailure()
                       << "pixel (" << x << ", " << y << ") differs: " << ta.size() << " vs "
                       << tb.size() << " terms; dominant policies\n  "
                       << describePolicy(a.dominantPolicy(x, y)) << "\n  "
                       << describePolicy(b.dominantPolicy(x, y));
        }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult sameImages(const Framebuffer &a, const Framebuffer &b, float tolerance) {
    if (a.width() != b.width() || a.height() != b.height())
        return ::testing::AssertionFailure() << "images differ in size";
    float worst = 0.f;
    int worstX = 0, worstY = 0, differing = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            float delta = 0.f;
            for (int c = 0; c < 3; ++c) {
                const float d = std::abs(a.at(x, y)[c] - b.at(x, y)[c]);
                delta = std::max(delta, std::isnan(d) ? std::numeric_limits<float>::infinity() : d);
            }
            if (delta > tolerance) ++differing;
            if (delta > worst) worst = delta, worstX = x, worstY = y;
        }
    if (differing == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << differing << " pixels differ by more than " << tolerance << "; worst " << worst
           << " at (" << worstX << ", " << worstY << ")";
}

// ---------------------------------------------------------------------------------------------
// Rendering

const ConformanceScene &conformanceScene() {
    static const ConformanceScene scene;
    return scene;
}

Framebuffer renderMap(const PolicyMap &map, int threads) {
    const ConformanceScene &scene = conformanceScene();
    RenderSettings settings;
    settings.width = map.width();
    settings.height = map.height();
    settings.samplesPerPixel = 1;
    settings.threads = threads;
    Framebuffer image;
    Renderer(scene.tracer).render(scene.camera, map, settings, image);
    return image;
}

Framebuffer renderStack(const LensStack &stack, int width, int height) {
    return renderMap(stack.compose(RayPolicy{}, width, height));
}

LensStack stackOf(std::initializer_list<std::shared_ptr<Lens>> lenses) {
    LensStack stack;
    for (const auto &lens : lenses) stack.add(lens);
    return stack;
}

} // namespace mvcl::test
