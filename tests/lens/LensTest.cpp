#include <mvcl/lens/Lens.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/core/Error.h>
#include <mvcl/model/LayerTable.h>

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace mvcl;
using test::errorOf;

namespace {

LensInfo testLensInfo() {
    LensInfo info;
    info.name = "probe";
    info.description = "a lens for testing the Lens base class";
    info.properties = {
        PropertyDecl::real("distance", 1.0, 0.0, 10.0, "scene units", "primary rays start here"),
        PropertyDecl::layers("casters", kAllLayers, "layers that cast shadows"),
        PropertyDecl::choice("shadows", "on", {"on", "off"}, "shadow rays at all"),
        PropertyDecl::boolean("failWith", false, "contribute() throws (testing only)"),
        PropertyDecl::integer("unused", 0, 0, 5, "", "declared but never read"),
    };
    info.defaultRayTypes = rayTypeBit(RayType::Primary) | rayTypeBit(RayType::Shadow);
    return info;
}

class ProbeLens : public Lens {
public:
    ProbeLens() : Lens(testLensInfo()) {}
    explicit ProbeLens(const LensInfo &info) : Lens(info) {}

protected:
    LensContribution contribute(const PropertyValues &properties,
                                const LensRegion &, const LensContext &) const override {
        if (properties.boolean("failWith")) throw std::runtime_error("probe failure");
        LensContribution contribution;
        contribution.visibility[size_t(RayType::Primary)].tMin = float(properties.real("distance"));
        contribution.visibility[size_t(RayType::Shadow)].layerMask = properties.layers("casters");
        contribution.shading.shadows = properties.choice("shadows") == "on";
        contribution.shading.reflections = false;
        contribution.sampleFromScreen[2][0] = 0.25f; // a shift, so primary shaping is visible
        contribution.color.offset = glm::vec3(0.5f);
        return contribution;
    }
};

// A lens whose contribute() reads a property it never declared.
class UndeclaredReadLens : public Lens {
public:
    UndeclaredReadLens() : Lens(testLensInfo()) {}

protected:
    LensContribution contribute(const PropertyValues &properties,
                                const LensRegion &, const LensContext &) const override {
        (void)properties.real("radius");
        return {};
    }
};

} // namespace

TEST(Lens, StartsOnDefaultsWithADisabledVersionZeroSnapshot) {
    ProbeLens lens;
    EXPECT_EQ(lens.typeName(), "probe");
    EXPECT_EQ(lens.label(), "probe");
    EXPECT_TRUE(lens.isEnabled());
    EXPECT_TRUE(lens.hasUncommittedChanges());
    const auto snapshot = lens.snapshot();
    ASSERT_NE(snapshot, nullptr);
    EXPECT_EQ(snapshot->version, 0u);
    EXPECT_FALSE(snapshot->enabled);
    EXPECT_TRUE(snapshot->contribution.isIdentity());
    // The declared table plus the common "rays", whose default comes from LensInfo.
    ASSERT_EQ(lens.properties().size(), 6u);
    EXPECT_EQ(lens.properties().back().name, "rays");
    EXPECT_EQ(lens.property("rays").toRayTypeSet(),
              rayTypeBit(RayType::Primary) | rayTypeBit(RayType::Shadow));
    EXPECT_EQ(lens.property("distance").toReal(), 1.0);
    EXPECT_EQ(lens.committedValues().size(), lens.properties().size());
}

TEST(Lens, SettersStageAndCommitPublishes) {
    ProbeLens lens;
    lens.commit();
    const auto first = lens.snapshot();
    EXPECT_EQ(first->version, 1u);
    EXPECT_TRUE(first->enabled);
    EXPECT_EQ(first->contribution.visibility[size_t(RayType::Primary)].tMin, 1.f);
    EXPECT_FALSE(lens.hasUncommittedChanges());

    lens.setProperty("distance", PropertyValue::real(4.5));
    lens.setPropertyText("casters", "2-");
    lens.setRegion(LensRegion::ellipse({0.3f, 0.3f}, {0.2f, 0.2f}));
    lens.setEnabled(false);
    EXPECT_TRUE(lens.hasUncommittedChanges());
    EXPECT_EQ(lens.property("distance").toReal(), 4.5);
    // Nothing reaches the renderer before commit().
    EXPECT_EQ(lens.snapshot(), first);
    EXPECT_EQ(lens.committedValues()[0], PropertyValue::real(1.0));

    lens.commit();
    const auto second = lens.snapshot();
    EXPECT_EQ(second->version, 2u);
    EXPECT_FALSE(second->enabled);
    EXPECT_EQ(second->region.shape(), LensRegion::Shape::Ellipse);
    EXPECT_EQ(second->contribution.visibility[size_t(RayType::Primary)].tMin, 4.5f);
    EXPECT_EQ(second->contribution.visibility[size_t(RayType::Shadow)].layerMask, layersFrom(2));
    EXPECT_EQ(lens.committedValues()[0], PropertyValue::real(4.5));
    // The old snapshot is immutable: holders of it still see the old state.
    EXPECT_EQ(first->contribution.visibility[size_t(RayType::Primary)].tMin, 1.f);

    lens.resetProperties();
    EXPECT_EQ(lens.property("distance").toReal(), 1.0);
    EXPECT_TRUE(lens.hasUncommittedChanges());
}

TEST(Lens, UnknownKeysAreErrorsNamingTheLensAndTheKnownKeys) {
    ProbeLens lens;
    EXPECT_EQ(errorOf([&] { lens.setProperty("distanse", PropertyValue::real(1.0)); }),
              "lens 'probe': unknown property 'distanse' (known: distance, casters, shadows, "
              "failWith, unused, rays)");
    EXPECT_THROW(lens.property("nope"), Error);
    EXPECT_THROW(lens.setPropertyText("nope", "1"), Error);
}

TEST(Lens, InvalidValuesAreRejectedWhenStaged) {
    ProbeLens lens;
    lens.setProperty("distance", PropertyValue::real(2.0));
    EXPECT_EQ(errorOf([&] { lens.setProperty("distance", PropertyValue::real(11.0)); }),
              "lens 'probe': property 'distance': 11 is outside [0, 10] scene units");
    EXPECT_THROW(lens.setProperty("distance", PropertyValue::integer(3)), Error);
    EXPECT_THROW(lens.setPropertyText("shadows", "tinted"), Error);
    EXPECT_THROW(lens.setPropertyText("casters", "1,40"), Error);
    EXPECT_THROW(lens.setPropertyText("rays", "camera"), Error);
    EXPECT_EQ(lens.property("distance").toReal(), 2.0); // unchanged by the failures
    EXPECT_EQ(lens.property("shadows").toChoice(), "on");
}

TEST(Lens, FailedCommitsKeepThePreviousSnapshot) {
    ProbeLens lens;
    lens.setProperty("distance", PropertyValue::real(3.0));
    lens.commit();
    const auto good = lens.snapshot();

    lens.setRegion(LensRegion::rectangle({0.5f, 0.5f}, {-0.1f, 0.2f}));
    const std::string regionError = errorOf([&] { lens.commit(); });
    EXPECT_NE(regionError.find("lens 'probe'"), std::string::npos) << regionError;
    EXPECT_NE(regionError.find("lens region"), std::string::npos) << regionError;
    EXPECT_EQ(lens.snapshot(), good);

    lens.setRegion(LensRegion());
    lens.setProperty("failWith", PropertyValue::boolean(true));
    const std::string pluginError = errorOf([&] { lens.commit(); });
    EXPECT_EQ(pluginError.rfind("lens 'probe': ", 0), 0u) << pluginError;
    EXPECT_NE(pluginError.find("probe failure"), std::string::npos) << pluginError;
    EXPECT_EQ(lens.snapshot(), good);
    EXPECT_EQ(lens.committedValues()[0], PropertyValue::real(3.0));
    EXPECT_TRUE(lens.hasUncommittedChanges());

    lens.setProperty("failWith", PropertyValue::boolean(false));
    lens.commit();
    EXPECT_EQ(lens.snapshot()->version, good->version + 1);
}

TEST(Lens, ReadingAnUndeclaredPropertyFailsTheCommit) {
    UndeclaredReadLens lens;
    const std::string error = errorOf([&] { lens.commit(); });
    EXPECT_EQ(error.rfind("lens 'probe': ", 0), 0u) << error;
    EXPECT_NE(error.find("'radius'"), std::string::npos) << error;
    EXPECT_EQ(lens.snapshot()->version, 0u);
}

TEST(Lens, RaysRestrictTheContribution) {
    ProbeLens lens;
    lens.setPropertyText("casters", "1");
    lens.commit(); // default rays: primary, shadow
    {
        const LensContribution &c = lens.snapshot()->contribution;
        EXPECT_EQ(c.visibility[size_t(RayType::Primary)].tMin, 1.f);
        EXPECT_EQ(c.visibility[size_t(RayType::Shadow)].layerMask, layerBit(1));
        EXPECT_EQ(c.shading.shadows, std::optional<bool>(true));
        EXPECT_FALSE(c.shading.reflections.has_value()); // reflection rays are not in the mask
        EXPECT_EQ(c.sampleFromScreen[2][0], 0.25f);
    }
    lens.setPropertyText("rays", "shadow,reflection");
    lens.commit();
    {
        const LensContribution &c = lens.snapshot()->contribution;
        EXPECT_EQ(c.visibility[size_t(RayType::Primary)].tMin, 0.f);
        EXPECT_EQ(c.sampleFromScreen, glm::mat3(1.f));
        EXPECT_EQ(c.visibility[size_t(RayType::Shadow)].layerMask, layerBit(1));
        EXPECT_EQ(c.shading.reflections, std::optional<bool>(false));
        EXPECT_EQ(c.color.offset, glm::vec3(0.5f)); // colour acts on the pixel and stays
    }
    lens.setPropertyText("rays", "none");
    lens.commit();
    {
        const LensContribution &c = lens.snapshot()->contribution;
        EXPECT_TRUE(c.shading.isEmpty());
        EXPECT_EQ(c.visibility[size_t(RayType::Shadow)].layerMask, kAllLayers);
        EXPECT_FALSE(c.isIdentity()); // only the colour is left
        EXPECT_EQ(c.color.offset, glm::vec3(0.5f));
    }
}

TEST(Lens, ReportsDeclaredPropertiesItNeverReads) {
    ProbeLens lens;
    EXPECT_TRUE(lens.unreadProperties().empty());
    lens.commit();
    EXPECT_EQ(lens.unreadProperties(), std::vector<std::string>{"unused"});
}

TEST(Lens, RejectsBadPropertyTables) {
    LensInfo declaresRays = testLensInfo();
    declaresRays.properties.push_back(PropertyDecl::rayTypes("rays", kAllRayTypes, "mine"));
    EXPECT_NE(errorOf([&] { ProbeLens lens(declaresRays); }).find("lens 'probe'"), std::string::npos);

    LensInfo duplicate = testLensInfo();
    duplicate.properties.push_back(PropertyDecl::boolean("distance", true, "again"));
    EXPECT_EQ(errorOf([&] { ProbeLens lens(duplicate); }),
              "lens 'probe': declares property 'distance' twice");

    LensInfo badDefault = testLensInfo();
    badDefault.properties[0].defaultValue = PropertyValue::real(20.0);
    EXPECT_NE(errorOf([&] { ProbeLens lens(badDefault); }).find("property 'distance'"),
              std::string::npos);

    LensInfo badRays = testLensInfo();
    badRays.defaultRayTypes = 0xff;
    EXPECT_THROW(ProbeLens lens(badRays), Error);
}

TEST(Lens, LabelIsIndependentOfTheType) {
    ProbeLens lens;
    lens.setLabel("left probe");
    EXPECT_EQ(lens.label(), "left probe");
    EXPECT_EQ(lens.typeName(), "probe");
    EXPECT_EQ(lens.info().description, "a lens for testing the Lens base class");
}

TEST(Lens, SnapshotsAreConsistentWhileAnotherThreadCommits) {
    ProbeLens lens;
    // Commits are cheap, so keep committing until the readers have seen plenty of them.
    constexpr int kMinimumCommits = 3000;
    constexpr long kMinimumReads = 20000;
    std::atomic<int> readersStarted{0};
    std::atomic<bool> done{false};
    std::atomic<int> inconsistent{0}, goneBack{0};
    std::atomic<long> reads{0};
    const auto reader = [&] {
        ++readersStarted;
        uint64_t lastVersion = 0;
        while (!done.load(std::memory_order_acquire)) {
            const std::shared_ptr<const LensSnapshot> snapshot = lens.snapshot();
            if (snapshot->version < lastVersion) ++goneBack;
            lastVersion = snapshot->version;
            // Commit v was made with distance = (v - 1) % 10 and casters = layer (v - 1) % 32.
            if (snapshot->version > 0) {
                const uint64_t i = snapshot->version - 1;
                const LensContribution &c = snapshot->contribution;
                if (c.visibility[size_t(RayType::Primary)].tMin != float(i % 10) ||
                    c.visibility[size_t(RayType::Shadow)].layerMask != layerBit(int(i % 32)))
                    ++inconsistent;
            }
            ++reads;
        }
    };
    std::thread first(reader), second(reader);
    while (readersStarted.load() < 2) std::this_thread::yield();
    int commits = 0;
    for (; commits < kMinimumCommits || (reads.load() < kMinimumReads && commits < 10'000'000);
         ++commits) {
        lens.setProperty("distance", PropertyValue::real(double(commits % 10)));
        lens.setProperty("casters", PropertyValue::layerSet(layerBit(commits % 32)));
        lens.commit();
    }
    done.store(true, std::memory_order_release);
    first.join();
    second.join();
    EXPECT_EQ(lens.snapshot()->version, uint64_t(commits));
    EXPECT_EQ(inconsistent.load(), 0);
    EXPECT_EQ(goneBack.load(), 0);
    EXPECT_GE(reads.load(), kMinimumReads);
}

TEST(LensContribution, ShadingOverrideSetsOnlyItsFields) {
    ShadingOverride override;
    EXPECT_TRUE(override.isEmpty());
    override.shadowStrength = 0.25f;
    override.maxDepth = 2;
    EXPECT_FALSE(override.isEmpty());
    ShadingPolicy shading;
    shading.shadows = false;
    shading.reflections = false;
    override.applyTo(shading);
    EXPECT_EQ(shading.shadowStrength, 0.25f);
    EXPECT_EQ(shading.maxDepth, 2);
    EXPECT_FALSE(shading.shadows);     // not set by the override: left as it was
    EXPECT_FALSE(shading.reflections); // likewise
    EXPECT_EQ(shading.shadowTint, ShadingPolicy{}.shadowTint);
}

TEST(LensContribution, IdentityAndRestriction) {
    EXPECT_TRUE(LensContribution{}.isIdentity());
    const auto changed = [](auto edit) {
        LensContribution c;
        edit(c);
        return !c.isIdentity();
    };
    EXPECT_TRUE(changed([](LensContribution &c) { c.sampleFromScreen[0][0] = 2.f; }));
    EXPECT_TRUE(changed([](LensContribution &c) { c.visibility[3].layerMask = 1u; }));
    EXPECT_TRUE(changed([](LensContribution &c) { c.visibility[1].tMax = 5.f; }));
    EXPECT_TRUE(changed([](LensContribution &c) { c.visibility[0].addClip(ClipVolume::sphere(glm::vec3(0.f), 1.f, ClipVolume::Keep::Outside)); }));
    EXPECT_TRUE(changed([](LensContribution &c) { c.shading.refractions = true; }));
    EXPECT_TRUE(changed([](LensContribution &c) { c.color.offset.x = 0.1f; }));

    LensContribution all;
    for (RayQuery &query : all.visibility) query.tMin = 1.f;
    all.sampleFromScreen[0][0] = 2.f;
    all.shading.shadows = false;
    all.shading.shadowTint = glm::vec3(1.f, 0.f, 0.f);
    all.shading.reflections = false;
    all.shading.refractions = false;
    all.shading.maxDepth = 1;
    const LensContribution refractionOnly = all.restrictedTo(rayTypeBit(RayType::Refraction));
    EXPECT_EQ(refractionOnly.visibility[size_t(RayType::Refraction)].tMin, 1.f);
    EXPECT_EQ(refractionOnly.visibility[size_t(RayType::Primary)].tMin, 0.f);
    EXPECT_EQ(refractionOnly.visibility[size_t(RayType::Shadow)].tMin, 0.f);
    EXPECT_EQ(refractionOnly.visibility[size_t(RayType::Reflection)].tMin, 0.f);
    EXPECT_EQ(refractionOnly.sampleFromScreen, glm::mat3(1.f));
    EXPECT_FALSE(refractionOnly.shading.shadows || refractionOnly.shading.shadowTint ||
                 refractionOnly.shading.reflections);
    EXPECT_EQ(refractionOnly.shading.refractions, std::optional<bool>(false));
    EXPECT_EQ(refractionOnly.shading.maxDepth, std::optional<int>(1));
    EXPECT_EQ(all.restrictedTo(kAllRayTypes).shading, all.shading);
    EXPECT_EQ(all.restrictedTo(kAllRayTypes).sampleFromScreen, all.sampleFromScreen);
}
