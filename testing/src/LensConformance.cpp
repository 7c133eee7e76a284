// The lens conformance checks: see LensConformance.h.

#include <mvcl/testing/LensConformance.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/core/Error.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace mvcl::test {

namespace {

/// Values a round trip must survive: the ends of finite ranges, every choice, every ray-type
/// mask, and random values.
std::vector<PropertyValue> roundTripValues(const PropertyDecl &decl, Random &random) {
    std::vector<PropertyValue> values{decl.defaultValue};
    switch (decl.type) {
    case PropertyType::Int:
        if (std::isfinite(decl.minimum) && std::abs(decl.minimum) < 1e9)
            values.push_back(PropertyValue::integer(int(decl.minimum)));
        if (std::isfinite(decl.maximum) && std::abs(decl.maximum) < 1e9)
            values.push_back(PropertyValue::integer(int(decl.maximum)));
        break;
    case PropertyType::Real:
        if (std::isfinite(decl.minimum)) values.push_back(PropertyValue::real(decl.minimum));
        if (std::isfinite(decl.maximum)) values.push_back(PropertyValue::real(decl.maximum));
        break;
    case PropertyType::Bool:
        values.push_back(PropertyValue::boolean(false));
        values.push_back(PropertyValue::boolean(true));
        break;
    case PropertyType::Choice:
        for (const std::string &choice : decl.choices) values.push_back(PropertyValue::choice(choice));
        return values;
    case PropertyType::LayerSet:
        values.push_back(PropertyValue::layerSet(0));
        values.push_back(PropertyValue::layerSet(kAllLayers));
        for (int first = 1; first < kMaxLayers; first += 5)
            values.push_back(PropertyValue::layerSet(layersFrom(first)));
        break;
    case PropertyType::RayTypeSet:
        for (unsigned mask = 0; mask < 16; ++mask)
            values.push_back(PropertyValue::rayTypeSet(uint8_t(mask)));
        return values;
    case PropertyType::Transform:
        values.push_back(PropertyValue::transform(glm::dmat4(1.0)));
        break;
    case PropertyType::Color:
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3:
        break;
    }
    for (int i = 0; i < 12; ++i) values.push_back(randomValidValue(decl, random));
    return values;
}

/// Texts that must not parse for a property of `type`.
std::vector<std::string> malformedTexts(PropertyType type) {
    switch (type) {
    case PropertyType::Bool: return {"maybe", "", "2"};
    case PropertyType::Int: return {"twelve", "", "1.5", "nan"};
    case PropertyType::Real: return {"twelve", "", "nan", "inf", "-inf"};
    case PropertyType::Color: return {"1,2", "red", "1,2,3,4", "nan,0,0"};
    case PropertyType::Choice: return {"no-such-choice", ""};
    case PropertyType::LayerSet: return {"32", "x-y", "-1"};
    case PropertyType::RayTypeSet: return {"sideways", "primary,diagonal"};
    case PropertyType::Point3:
    case PropertyType::Vector3: return {"1,2", "1,2,3,4", "x,y,z", "nan,0,0", "1,inf,0", ""};
    case PropertyType::Box3: return {"0,0,0,1,1", "0,0,0,1,1,1,1", "1,0,0,0,1,1", "0,0,0,1,nan,1"};
    case PropertyType::Transform: return {"identity,1", "1,0,0,0,0,1,0,0,0,0,1", "0,0,0,0,0,0,0,0,0,0,0,0", "rotate"};
    }
    return {};
}

/// Typed values outside the declared range of `decl`.
std::vector<PropertyValue> outOfRangeValues(const PropertyDecl &decl) {
    std::vector<PropertyValue> values;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    switch (decl.type) {
    case PropertyType::Int:
        if (std::isfinite(decl.minimum) && decl.minimum > -2e9)
            values.push_back(PropertyValue::integer(int(decl.minimum) - 1));
        if (std::isfinite(decl.maximum) && decl.maximum < 2e9)
            values.push_back(PropertyValue::integer(int(decl.maximum) + 1));
        break;
    case PropertyType::Real:
        if (std::isfinite(decl.minimum))
            values.push_back(PropertyValue::real(decl.minimum - (1.0 + std::abs(decl.minimum))));
        if (std::isfinite(decl.maximum))
            values.push_back(PropertyValue::real(decl.maximum + (1.0 + std::abs(decl.maximum))));
        values.push_back(PropertyValue::real(nan));
        values.push_back(PropertyValue::real(std::numeric_limits<double>::infinity()));
        break;
    case PropertyType::Color:
        if (std::isfinite(decl.minimum))
            values.push_back(PropertyValue::color({float(decl.minimum) - 1.f, 0.5f, 0.5f}));
        values.push_back(PropertyValue::color({0.5f, float(nan), 0.5f}));
        break;
    case PropertyType::Choice:
        values.push_back(PropertyValue::choice("no-such-choice"));
        break;
    case PropertyType::RayTypeSet:
        values.push_back(PropertyValue::rayTypeSet(0x10)); // no fifth ray type
        break;
    case PropertyType::Point3:
    case PropertyType::Vector3: {
        const auto make = [&](const glm::dvec3 &v) {
            return decl.type == PropertyType::Point3 ? PropertyValue::point3(v) : PropertyValue::vector3(v);
        };
        if (std::isfinite(decl.minimum)) values.push_back(make({0.0, decl.minimum - 1.0, 0.0}));
        if (std::isfinite(decl.maximum)) values.push_back(make({decl.maximum + 1.0, 0.0, 0.0}));
        values.push_back(make({0.0, 0.0, nan}));
        values.push_back(make({std::numeric_limits<double>::infinity(), 0.0, 0.0}));
        break;
    }
    case PropertyType::Box3:
        values.push_back(PropertyValue::box3({{1.0, 0.0, 0.0}, {0.0, 1.0, 1.0}})); // min > max
        values.push_back(PropertyValue::box3({{0.0, nan, 0.0}, {1.0, 1.0, 1.0}}));
        if (std::isfinite(decl.minimum))
            values.push_back(PropertyValue::box3({{decl.minimum - 1.0, 0.0, 0.0}, {decl.minimum, 1.0, 1.0}}));
        break;
    case PropertyType::Transform: {
        values.push_back(PropertyValue::transform(glm::dmat4(0.0))); // not invertible
        glm::dmat4 m(1.0);
        m[3][1] = nan;
        values.push_back(PropertyValue::transform(m));
        break;
    }
    case PropertyType::Bool:
    case PropertyType::LayerSet: // every mask is a valid layer set
        break;
    }
    return values;
}

PropertyValue sampleValueOfType(PropertyType type) {
    switch (type) {
    case PropertyType::Bool: return PropertyValue::boolean(true);
    case PropertyType::Int: return PropertyValue::integer(1);
    case PropertyType::Real: return PropertyValue::real(0.5);
    case PropertyType::Color: return PropertyValue::color(glm::vec3(0.5f));
    case PropertyType::Choice: return PropertyValue::choice("x");
    case PropertyType::LayerSet: return PropertyValue::layerSet(1);
    case PropertyType::RayTypeSet: return PropertyValue::rayTypeSet(1);
    case PropertyType::Point3: return PropertyValue::point3({1.0, 2.0, 3.0});
    case PropertyType::Vector3: return PropertyValue::vector3({0.0, 0.0, 1.0});
    case PropertyType::Box3: return PropertyValue::box3({{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}});
    case PropertyType::Transform: return PropertyValue::transform(glm::dmat4(1.0));
    }
    return {};
}

constexpr PropertyType kAllPropertyTypes[] = {
    PropertyType::Bool,       PropertyType::Int,    PropertyType::Real,    PropertyType::Color,
    PropertyType::Choice,     PropertyType::LayerSet, PropertyType::RayTypeSet, PropertyType::Point3,
    PropertyType::Vector3,    PropertyType::Box3,   PropertyType::Transform};

/// A copy of `lens`'s committed properties in a new lens from `create`, over `region`.
std::shared_ptr<Lens> cloneWithRegion(const LensFactory &create, const Lens &lens,
                                      const LensRegion &region) {
    std::shared_ptr<Lens> copy = create();
    const std::vector<PropertyValue> values = lens.committedValues();
    for (std::size_t i = 0; i < values.size(); ++i)
        copy->setProperty(lens.properties()[i].name, values[i]);
    copy->setRegion(region);
    copy->commit();
    return copy;
}

} // namespace

::testing::AssertionResult checkDefaults(const std::string &typeName, const LensFactory &create) {
    const std::shared_ptr<Lens> lens = create();
    if (!lens) return ::testing::AssertionFailure() << "the factory returned null";
    const auto snapshot = lens->snapshot();
    if (!snapshot || snapshot->version < 1)
        return ::testing::AssertionFailure() << "a new lens is not committed";
    if (const std::string fault = lens->fault(); !fault.empty())
        return ::testing::AssertionFailure() << "its contribution on the defaults fails, so it is disabled: " << fault;
    if (!snapshot->enabled || !lens->isEnabled())
        return ::testing::AssertionFailure() << "a new lens is not enabled";
    if (lens->typeName() != typeName || lens->info().name != typeName)
        return ::testing::AssertionFailure()
               << "type name '" << lens->typeName() << "' differs from '" << typeName << "'";
    if (lens->hasUncommittedChanges())
        return ::testing::AssertionFailure() << "a new lens has uncommitted changes";
    const PropertyTable &table = lens->properties();
    const PropertyDecl *rays = findProperty(table, "rays");
    if (!rays || rays->type != PropertyType::RayTypeSet ||
        rays->defaultValue != PropertyValue::rayTypeSet(lens->info().defaultRayTypes))
        return ::testing::AssertionFailure()
               << "the common 'rays' property is missing or not on LensInfo::defaultRayTypes";
    if (table.size() != lens->info().properties.size() + 1)
        return ::testing::AssertionFailure() << "properties() is not the declared table plus 'rays'";
    const std::vector<PropertyValue> committed = lens->committedValues();
    if (committed.size() != table.size())
        return ::testing::AssertionFailure() << "committedValues() has " << committed.size()
                                             << " values for " << table.size() << " properties";
    for (std::size_t i = 0; i < table.size(); ++i) {
        const PropertyDecl &decl = table[i];
        if (const auto error = errorFrom([&] { decl.validate(decl.defaultValue); }))
            return ::testing::AssertionFailure() << "default of '" << decl.name
                                                 << "' does not validate: " << *error;
        if (lens->property(decl.name) != decl.defaultValue || committed[i] != decl.defaultValue)
            return ::testing::AssertionFailure() << "'" << decl.name << "' is not on its default";
    }
    const std::vector<std::string> unread = lens->unreadProperties();
    if (!unread.empty()) {
        auto failure = ::testing::AssertionFailure() << "contribute() never reads:";
        for (const std::string &name : unread) failure << " " << name;
        return failure;
    }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkPropertyRoundTrip(const LensFactory &create, Random &random) {
    const std::shared_ptr<Lens> lens = create();
    const PropertyTable &table = lens->properties();
    for (std::size_t i = 0; i < table.size(); ++i) {
        const PropertyDecl &decl = table[i];
        for (const PropertyValue &value : roundTripValues(decl, random)) {
            const std::string text = value.toString();
            const uint64_t versionBefore = lens->snapshot()->version;
            if (const auto error = errorFrom([&] {
                    lens->setPropertyText(decl.name, text);
                    lens->commit();
                }))
                return ::testing::AssertionFailure() << decl.name << "=" << text << " rejected: " << *error;
            if (lens->property(decl.name) != value)
                return ::testing::AssertionFailure()
                       << decl.name << "=" << text << " reads back as " << lens->property(decl.name).toString();
            if (lens->committedValues().at(i) != value)
                return ::testing::AssertionFailure() << decl.name << "=" << text << " was not committed";
            if (lens->snapshot()->version != versionBefore + 1)
                return ::testing::AssertionFailure() << "commit() did not advance the version by one";
        }
    }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkRejectsBadValues(const LensFactory &create) {
    const std::shared_ptr<Lens> lens = create();
    const std::string lensName = lens->typeName();
    const auto rejects = [&](const std::string &what, const std::string &key,
                             const std::function<void()> &action) -> ::testing::AssertionResult {
        const auto snapshotBefore = lens->snapshot();
        const std::vector<PropertyValue> stagedBefore = [&] {
            std::vector<PropertyValue> staged;
            for (const PropertyDecl &decl : lens->properties()) staged.push_back(lens->property(decl.name));
            return staged;
        }();
        const auto error = errorFrom(action);
        if (!error) return ::testing::AssertionFailure() << what << " was accepted";
        if (error->find(lensName) == std::string::npos || error->find(key) == std::string::npos)
            return ::testing::AssertionFailure() << what << ": error '" << *error
                                                 << "' does not name lens '" << lensName
                                                 << "' and key '" << key << "'";
        if (lens->snapshot() != snapshotBefore)
            return ::testing::AssertionFailure() << what << " replaced the committed snapshot";
        for (std::size_t i = 0; i < stagedBefore.size(); ++i)
            if (lens->property(lens->properties()[i].name) != stagedBefore[i])
                return ::testing::AssertionFailure() << what << " changed the staged '"
                                                     << lens->properties()[i].name << "'";
        if (lens->hasUncommittedChanges())
            return ::testing::AssertionFailure() << what << " left uncommitted changes";
        return ::testing::AssertionSuccess();
    };

    for (const std::string key : {"noSuchProperty", "", "rays.primary"}) {
        for (const auto &result :
             {rejects("unknown key '" + key + "' (setProperty)", key,
                      [&] { lens->setProperty(key, PropertyValue::boolean(true)); }),
              rejects("unknown key '" + key + "' (setPropertyText)", key,
                      [&] { lens->setPropertyText(key, "true"); }),
              rejects("unknown key '" + key + "' (property)", key, [&] { (void)lens->property(key); })})
            if (!result) return result;
    }
    for (const PropertyDecl &decl : lens->properties()) {
        for (const PropertyType other : kAllPropertyTypes) {
            if (other == decl.type) continue;
            const PropertyValue wrong = sampleValueOfType(other);
            if (auto result = rejects(std::string(propertyTypeName(other)) + " value for " +
                                          propertyTypeName(decl.type) + " '" + decl.name + "'",
                                      decl.name, [&] { lens->setProperty(decl.name, wrong); });
                !result)
                return result;
        }
        for (const PropertyValue &value : outOfRangeValues(decl))
            if (auto result = rejects(decl.name + "=" + value.toString() + " (out of range " +
                                          decl.rangeText() + ")",
                                      decl.name, [&] { lens->setProperty(decl.name, value); });
                !result)
                return result;
        for (const std::string &text : malformedTexts(decl.type))
            if (auto result = rejects(decl.name + "='" + text + "'", decl.name,
                                      [&] { lens->setPropertyText(decl.name, text); });
                !result)
                return result;
    }

    // A broken region is caught by setRegion() or at the latest by commit(); either way the
    // committed snapshot stays. (A region of size 0 is valid: an empty lens, see (e).)
    const auto snapshotBefore = lens->snapshot();
    LensRegion negative = LensRegion::rectangle({0.5f, 0.5f}, {-0.1f, 0.2f});
    const auto error = errorFrom([&] {
        lens->setRegion(negative);
        lens->commit();
    });
    if (!error) return ::testing::AssertionFailure() << "a region of negative width was committed";
    if (lens->snapshot() != snapshotBefore)
        return ::testing::AssertionFailure() << "a failed commit replaced the snapshot";
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkDisabledChangesNothing(const LensFactory &create, Random &random) {
    for (int trial = 0; trial < 3; ++trial) {
        const auto below = randomLens(create, random, trial == 2 ? 3.f : 0.f);
        const auto disabled = randomLens(create, random, trial == 1 ? 3.f : 0.f);
        disabled->setEnabled(false);
        disabled->commit();
        if (disabled->snapshot()->enabled)
            return ::testing::AssertionFailure() << "setEnabled(false) + commit() left it enabled";
        const LensStack reference = stackOf({below});
        const PolicyMap expected = reference.compose(RayPolicy{}, kConformanceWidth, kConformanceHeight);
        for (const LensStack &stack : {stackOf({below, disabled}), stackOf({disabled, below})}) {
            const PolicyMap actual = stack.compose(RayPolicy{}, kConformanceWidth, kConformanceHeight);
            if (auto same = samePolicyMaps(actual, expected); !same)
                return same << " (disabled " << describeValues(*disabled) << ")";
            if (auto same = sameImages(renderMap(actual), renderMap(expected), 0.f); !same)
                return same << " (disabled " << describeValues(*disabled) << ")";
        }
    }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkOutsideImageChangesNothing(const LensFactory &create,
                                                           Random &random) {
    const PolicyMap base(kConformanceWidth, kConformanceHeight, RayPolicy{});
    const Framebuffer baseImage = renderMap(base);
    std::vector<LensRegion> outside{
        LensRegion::rectangle({1.6f, 0.5f}, {0.5f, 0.5f}),
        LensRegion::ellipse({0.5f, -0.8f}, {0.9f, 0.9f}),
        LensRegion::polygon({{-0.5f, -0.5f}, {-0.1f, -0.5f}, {-0.3f, 1.5f}}),
        // Empty regions in the middle of the image: no effect either, and not an error.
        LensRegion::rectangle({0.5f, 0.5f}, {0.f, 0.3f}),
        LensRegion::ellipse({0.5f, 0.5f}, {0.f, 0.f}),
        LensRegion::polygon({{0.2f, 0.5f}, {0.5f, 0.5f}, {0.8f, 0.5f}})};
    outside[1].setFeather(4.f);
    outside[4].setFeather(4.f);
    for (const LensRegion &region : outside) {
        const auto lens = randomLens(create, random);
        lens->setRegion(region);
        lens->commit();
        const PolicyMap map = stackOf({lens}).compose(RayPolicy{}, kConformanceWidth, kConformanceHeight);
        if (auto same = samePolicyMaps(map, base); !same) return same << " (" << describeValues(*lens) << ")";
        if (auto same = sameImages(renderMap(map), baseImage, 0.f); !same)
            return same << " (" << describeValues(*lens) << ")";
    }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkIdempotence(const LensFactory &create, Random &random) {
    if (!create()->info().algebra.idempotent)
        return ::testing::AssertionSuccess() << "not declared idempotent";
    for (int trial = 0; trial < 4; ++trial) {
        // Half the trials feathered: idempotence must hold across the feather band too.
        const auto once = randomLens(create, random, trial % 2 ? 4.f : 0.f);
        // A lens that changes nothing (e.g. rays=none) is left out of the stack: nothing to check.
        if (once->snapshot()->contribution.isIdentity()) continue;
        const auto sameRegion = cloneWithRegion(create, *once, once->region());
        const auto otherRegion = cloneWithRegion(create, *once, randomCentralRegion(random));
        const Framebuffer single = renderStack(stackOf({once}));
        if (auto same = sameImages(renderStack(stackOf({once, sameRegion})), single, kAlgebraTolerance); !same)
            return same << " stacking " << describeValues(*once) << " twice over one region";

        const PolicyMap twiceMap = stackOf({once, otherRegion}).compose(RayPolicy{}, kConformanceWidth, kConformanceHeight);
        const Framebuffer twice = renderMap(twiceMap);
        int overlapPixels = 0;
        for (int y = 0; y < kConformanceHeight; ++y)
            for (int x = 0; x < kConformanceWidth; ++x) {
                if (twiceMap.terms(x, y).size() != 1 || twiceMap.dominantPolicy(x, y).lensSet != 0b11) continue;
                ++overlapPixels;
                for (int c = 0; c < 3; ++c)
                    if (!(std::abs(twice.at(x, y)[c] - single.at(x, y)[c]) <= kAlgebraTolerance))
                        return ::testing::AssertionFailure()
                               << "pixel (" << x << ", " << y << ") under two overlapping "
                               << describeValues(*once) << " differs from one: "
                               << twice.at(x, y)[c] << " vs " << single.at(x, y)[c];
            }
        if (overlapPixels == 0)
            return ::testing::AssertionFailure() << "test setup: the regions do not overlap";
    }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkCommutes(const LensSubject &subject,
                                         const std::vector<LensSubject> &others, Random &random) {
    if (!subject.create()->info().algebra.commutes)
        return ::testing::AssertionSuccess() << "not declared commutative";
    std::vector<LensSubject> partners{subject};
    for (const LensSubject &other : others)
        if (other.name != subject.name && other.create()->info().algebra.commutes) partners.push_back(other);
    for (const LensSubject &partner : partners)
        for (int trial = 0; trial < 3; ++trial) {
            const auto a = randomLens(subject.create, random, trial == 2 ? 3.f : 0.f);
            auto b = randomLens(partner.create, random, trial == 1 ? 3.f : 0.f);
            // Against itself, draw until the two lenses differ, or the swap proves nothing.
            for (int redraw = 0; partner.name == subject.name && redraw < 20 &&
                                 b->committedValues() == a->committedValues();
                 ++redraw)
                b = randomLens(partner.create, random);
            const Framebuffer ab = renderStack(stackOf({a, b}));
            const Framebuffer ba = renderStack(stackOf({b, a}));
            if (auto same = sameImages(ab, ba, kAlgebraTolerance); !same)
                return same << " swapping " << describeValues(*a) << " and " << describeValues(*b);
        }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkRayTypeMask(const LensFactory &create, Random &random) {
    for (int trial = 0; trial < 3; ++trial) {
        const auto lens = randomLens(create, random);
        lens->setProperty("rays", PropertyValue::rayTypeSet(kAllRayTypes));
        lens->commit();
        const LensContribution full = lens->snapshot()->contribution;
        for (unsigned mask = 0; mask < 16; ++mask) {
            lens->setProperty("rays", PropertyValue::rayTypeSet(uint8_t(mask)));
            lens->commit();
            const LensContribution &c = lens->snapshot()->contribution;
            const auto has = [&](RayType type) { return (mask & rayTypeBit(type)) != 0; };
            const auto fail = [&](const char *what) {
                return ::testing::AssertionFailure()
                       << what << " with rays=" << rayTypeSetToString(uint8_t(mask)) << " for "
                       << describeValues(*lens);
            };
            for (int t = 0; t < kRayTypeCount; ++t) {
                const RayQuery expected = has(RayType(t)) ? full.visibility[t] : RayQuery{};
                if (!(c.visibility[t] == expected)) return fail("visibility of a ray type is wrong");
            }
            if (c.sampleFromScreen != (has(RayType::Primary) ? full.sampleFromScreen : glm::mat3(1.f)))
                return fail("ray shaping is wrong");
            const bool shadow = has(RayType::Shadow);
            if (c.shading.shadows != (shadow ? full.shading.shadows : std::nullopt) ||
                c.shading.shadowStrength != (shadow ? full.shading.shadowStrength : std::nullopt) ||
                c.shading.shadowTint != (shadow ? full.shading.shadowTint : std::nullopt))
                return fail("shadow shading is wrong");
            if (c.shading.reflections != (has(RayType::Reflection) ? full.shading.reflections : std::nullopt) ||
                c.shading.refractions != (has(RayType::Refraction) ? full.shading.refractions : std::nullopt))
                return fail("secondary-ray switches are wrong");
            if (!(c.color == full.color)) return fail("the colour stage was dropped");
        }

        // rays = none, rendered: only the colour stage may remain.
        lens->setProperty("rays", PropertyValue::rayTypeSet(0));
        lens->commit();
        const PolicyMap base(kConformanceWidth, kConformanceHeight, RayPolicy{});
        const PolicyMap map = stackOf({lens}).compose(RayPolicy{}, kConformanceWidth, kConformanceHeight);
        if (full.color.isIdentity()) {
            if (auto same = samePolicyMaps(map, base); !same) return same << " with rays=none";
            if (auto same = sameImages(renderMap(map), renderMap(base), 0.f); !same)
                return same << " with rays=none for " << describeValues(*lens);
        } else {
            for (const PixelPolicy &policy : map.policies()) {
                PixelPolicy withoutColor = policy;
                withoutColor.ray.color = ColorPolicy{};
                if (!withoutColor.rendersLike(PixelPolicy{}))
                    return ::testing::AssertionFailure()
                           << "with rays=none a policy changes more than colour: "
                           << describePolicy(policy);
            }
        }
    }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult checkThreadSafety(const LensFactory &create, Random &random, int commits) {
    const std::shared_ptr<Lens> lens = create();
    lens->setRegion(LensRegion::rectangle({0.5f, 0.5f}, {0.5f, 0.5f}));
    lens->commit();
    const LensStack stack = stackOf({lens});
    constexpr int kWidth = 16, kHeight = 12;

    std::vector<std::shared_ptr<const LensSnapshot>> committed{lens->snapshot()};
    std::atomic<bool> writing{true};
    struct Observations {
        std::vector<PixelPolicy> policies;
        bool versionWentBack = false;
        std::atomic<int> composes{0};
    };
    Observations seen[2];
    const auto read = [&](Observations &out, bool render) {
        uint64_t lastVersion = 0;
        do {
            const uint64_t version = lens->snapshot()->version;
            out.versionWentBack |= version < lastVersion;
            lastVersion = version;
            const PolicyMap map = stack.compose(RayPolicy{}, kWidth, kHeight);
            const PixelPolicy &centre = map.dominantPolicy(kWidth / 2, kHeight / 2);
            if (out.policies.empty() || !out.policies.back().rendersLike(centre))
                out.policies.push_back(centre);
            if (render) (void)renderMap(map, 1);
            ++out.composes;
        } while (writing.load());
    };
    std::thread composer(read, std::ref(seen[0]), false);
    std::thread renderer(read, std::ref(seen[1]), true);
    Random writerRandom(random());
    // Keep committing until both readers have overlapped with the writer for a while, so the
    // check cannot pass just because the writer finished before the readers started.
    constexpr int kMinimumComposes = 20, kMaximumCommits = 200000;
    const auto readersBusyEnough = [&] {
        return seen[0].composes >= kMinimumComposes && seen[1].composes >= kMinimumComposes;
    };
    int commitCount = 0;
    for (; commitCount < kMaximumCommits && (commitCount < commits || !readersBusyEnough());
         ++commitCount) {
        const PropertyTable &table = lens->properties();
        const PropertyDecl &decl = table[writerRandom() % table.size()];
        lens->setProperty(decl.name, randomValidValue(decl, writerRandom));
        if (writerRandom() % 8 == 0) lens->setEnabled(!lens->isEnabled());
        lens->commit();
        committed.push_back(lens->snapshot());
    }
    writing = false;
    composer.join();
    renderer.join();

    std::vector<PixelPolicy> possible;
    for (const auto &snapshot : committed)
        possible.push_back(snapshot->enabled ? applyContribution(PixelPolicy{}, snapshot->contribution)
                                             : PixelPolicy{});
    if (!readersBusyEnough())
        return ::testing::AssertionFailure() << "the readers did not get to run during the commits";
    for (const Observations &observations : seen) {
        if (observations.versionWentBack)
            return ::testing::AssertionFailure() << "a reader saw the snapshot version decrease";
        for (const PixelPolicy &policy : observations.policies)
            if (std::none_of(possible.begin(), possible.end(),
                             [&](const PixelPolicy &p) { return p.rendersLike(policy); }))
                return ::testing::AssertionFailure()
                       << "a composed policy matches no committed snapshot: " << describePolicy(policy);
    }
    return ::testing::AssertionSuccess() << seen[0].composes << " + " << seen[1].composes
                                         << " composes during " << commitCount << " commits";
}

::testing::AssertionResult checkDocumented(const LensFactory &create) {
    const std::shared_ptr<Lens> lens = create();
    if (lens->info().description.empty())
        return ::testing::AssertionFailure() << "LensInfo::description is empty";
    std::vector<std::string> names;
    for (const PropertyDecl &decl : lens->properties()) {
        const auto fail = [&](const char *what) {
            return ::testing::AssertionFailure() << "property '" << decl.name << "': " << what;
        };
        if (decl.doc.empty()) return fail("doc is empty");
        if (decl.name.empty() || !std::islower(static_cast<unsigned char>(decl.name[0])) ||
            !std::all_of(decl.name.begin(), decl.name.end(),
                         [](char c) { return std::isalnum(static_cast<unsigned char>(c)); }))
            return fail("name is not lowerCamelCase");
        if (std::find(names.begin(), names.end(), decl.name) != names.end())
            return fail("declared twice");
        // On the command line (--lens type:key=value,...) region keys come first.
        for (const char *regionKey : {"shape", "center", "size", "points", "feather", "outline", "outlineColor",
                                      "label", "enabled"})
            if (decl.name == regionKey) return fail("name is taken by the lens region or lens on the command line");
        names.push_back(decl.name);
        if (decl.type != decl.defaultValue.type()) return fail("default has another type");
        if (decl.rangeText().empty()) return fail("rangeText() is empty");
        if (decl.type == PropertyType::Int || decl.type == PropertyType::Real) {
            if (!std::isfinite(decl.minimum) || std::isnan(decl.maximum) ||
                decl.maximum == -std::numeric_limits<double>::infinity() ||
                decl.minimum > decl.maximum)
                return fail("range is not [finite minimum, maximum or +infinity]");
        }
        if (decl.type == PropertyType::Choice &&
            (decl.choices.size() < 2 ||
             std::find(decl.choices.begin(), decl.choices.end(), decl.defaultValue.toChoice()) ==
                 decl.choices.end()))
            return fail("a choice needs at least two options, the default among them");
        // Spaces and conditions name a Choice of the same lens, and only its choices: editors
        // (the viewer's 3D handles) place values by them.
        const auto choiceNamed = [&](const std::string &name) {
            const PropertyDecl *choice = findProperty(lens->properties(), name);
            return choice && choice->type == PropertyType::Choice ? choice : nullptr;
        };
        const auto offers = [](const PropertyDecl &choice, const std::string &value) {
            return std::find(choice.choices.begin(), choice.choices.end(), value) != choice.choices.end();
        };
        if (!decl.spaceFrom.property.empty()) {
            const PropertyDecl *choice = choiceNamed(decl.spaceFrom.property);
            if (!choice) return fail("spaceFrom names no Choice property");
            for (const auto &[value, space] : decl.spaceFrom.spaces)
                if (!offers(*choice, value)) return fail("spaceFrom maps a value its choice does not offer");
            for (const std::string &value : choice->choices)
                if (std::none_of(decl.spaceFrom.spaces.begin(), decl.spaceFrom.spaces.end(),
                                 [&](const auto &entry) { return entry.first == value; }))
                    return fail("spaceFrom leaves a choice without a space");
            const auto chosen = std::find_if(decl.spaceFrom.spaces.begin(), decl.spaceFrom.spaces.end(),
                                             [&](const auto &entry) { return entry.first == choice->defaultValue.toChoice(); });
            if (chosen->second != decl.space) return fail("space is not the one spaceFrom gives on the defaults");
        }
        if (!decl.usedWhen.property.empty()) {
            const PropertyDecl *choice = choiceNamed(decl.usedWhen.property);
            if (!choice) return fail("usedWhen names no Choice property");
            if (!offers(*choice, decl.usedWhen.value)) return fail("usedWhen asks for a value its choice does not offer");
        }
    }
    if (findProperty(lens->info().properties, "rays"))
        return ::testing::AssertionFailure() << "declares 'rays' itself (Lens adds it)";
    return ::testing::AssertionSuccess();
}

namespace {
// What a contribution does to the default policy; contributions have no operator==.
PixelPolicy appliedToDefault(const LensSnapshot &snapshot) {
    PixelPolicy p = applyContribution(PixelPolicy{}, snapshot.contribution);
    p.lensSet = snapshot.enabled ? 1 : 0;
    return p;
}
} // namespace

::testing::AssertionResult checkContext(const LensFactory &create, Random &random) {
    const ConformanceScene &scene = conformanceScene();
    LensContext here = LensContext::forScene(scene.scene);
    here.camera = scene.scene.cameras.front();
    here.imageWidth = kConformanceWidth;
    here.imageHeight = kConformanceHeight;
    LensContext there = here; // another view of the same scene
    there.camera.eye = here.camera.eye + glm::vec3(1.5f, -1.f, 0.5f);
    there.camera.verticalFovDegrees = here.camera.verticalFovDegrees * 0.7f;
    there.imageWidth = 2 * kConformanceWidth;
    there.imageHeight = kConformanceHeight + 10;
    for (int trial = 0; trial < 4; ++trial) {
        const std::shared_ptr<Lens> lens = randomLens(create, random);
        lens->setContext(here);
        lens->commit();
        if (lens->hasUncommittedChanges())
            return ::testing::AssertionFailure() << "a commit left the context uncommitted";
        if (lens->snapshotIn(here) != lens->snapshot())
            return ::testing::AssertionFailure() << "snapshotIn() of the committed context is not snapshot()";
        const std::shared_ptr<const LensSnapshot> inThere = lens->snapshotIn(there);
        if (lens->snapshotIn(there) != inThere)
            return ::testing::AssertionFailure() << "snapshotIn() of the same context twice made two snapshots";
        const std::shared_ptr<Lens> committedThere = cloneWithRegion(create, *lens, lens->region());
        committedThere->setContext(there);
        committedThere->commit();
        if (!appliedToDefault(*inThere).rendersLike(appliedToDefault(*committedThere->snapshot())) ||
            inThere->enabled != committedThere->snapshot()->enabled)
            return ::testing::AssertionFailure() << "snapshotIn(another view) differs from a commit in that view ("
                                                 << describeValues(*lens) << ")";
        if (!lens->info().dependsOnView &&
            !appliedToDefault(*lens->snapshot()).rendersLike(appliedToDefault(*committedThere->snapshot())))
            return ::testing::AssertionFailure()
                   << "the contribution changes with the camera or image size, but LensInfo::dependsOnView is "
                      "not set ("
                   << describeValues(*lens) << ")";
    }
    return ::testing::AssertionSuccess();
}

} // namespace mvcl::test
