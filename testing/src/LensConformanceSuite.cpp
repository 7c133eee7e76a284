// The conformance checks as GoogleTest tests: see LensConformanceSuite.h.

#include <mvcl/testing/LensConformanceSuite.h>

#include <gtest/gtest.h>

#include <memory>
#include <utility>

namespace mvcl::test {

namespace {

/// The fixture every registered test shares: it runs one check on one subject.
class ConformanceTest : public ::testing::Test {
public:
    ConformanceTest(const ConformanceCheck &check, LensSubject subject,
                    std::function<std::vector<LensSubject>()> partners)
        : m_check(check), m_subject(std::move(subject)), m_partners(std::move(partners)) {}

    void TestBody() override {
        const std::vector<LensSubject> partners = m_partners ? m_partners() : std::vector<LensSubject>{};
        const ::testing::AssertionResult result = m_check.run(m_subject, partners);
        if (!result)
            ADD_FAILURE() << "lens type '" << m_subject.name << "' fails conformance check '" << m_check.name
                          << "': " << result.message();
        else if (result.message()[0] != '\0')
            RecordProperty("result", result.message());
    }

private:
    const ConformanceCheck &m_check;
    LensSubject m_subject;
    std::function<std::vector<LensSubject>()> m_partners;
};

/// A check that draws random values, seeded per lens type and `seed` (short names, kept stable
/// so that a lens's random cases stay the same from release to release).
template <class Check> ConformanceCheck withRandom(std::string name, std::string seed, Check check) {
    return {std::move(name), [check, seed](const LensSubject &subject, const std::vector<LensSubject> &) {
                Random random = randomFor(subject.name, seed);
                return check(subject.create, random);
            }};
}

} // namespace

const std::vector<ConformanceCheck> &conformanceChecks() {
    static const std::vector<ConformanceCheck> checks{
        {"DefaultsBuildACommittedLensThatReadsEveryParameter",
         [](const LensSubject &subject, const std::vector<LensSubject> &) {
             return checkDefaults(subject.name, subject.create);
         }},
        withRandom("EveryPropertyRoundTripsThroughItsText", "round-trip", checkPropertyRoundTrip),
        {"RejectsUnknownKeysWrongTypesAndOutOfRangeValues",
         [](const LensSubject &subject, const std::vector<LensSubject> &) {
             return checkRejectsBadValues(subject.create);
         }},
        withRandom("DisabledLensChangesNothing", "disabled", checkDisabledChangesNothing),
        withRandom("LensOutsideTheImageChangesNothing", "outside", checkOutsideImageChangesNothing),
        withRandom("DeclaredIdempotenceHoldsWhenRendered", "idempotent", checkIdempotence),
        {"DeclaredCommutativityHoldsWhenRendered",
         [](const LensSubject &subject, const std::vector<LensSubject> &partners) {
             Random random = randomFor(subject.name, "commutes");
             return checkCommutes(subject, partners, random);
         }},
        withRandom("RayTypeMaskIsHonoured", "rays", checkRayTypeMask),
        {"CommitsWhileOtherThreadsComposeAndRender",
         [](const LensSubject &subject, const std::vector<LensSubject> &) {
             Random random = randomFor(subject.name, "threads");
             return checkThreadSafety(subject.create, random);
         }},
        withRandom("ContextAndViewDependenceAreHonoured", "context", checkContext),
        {"PropertyTableIsDocumented",
         [](const LensSubject &subject, const std::vector<LensSubject> &) { return checkDocumented(subject.create); }},
    };
    return checks;
}

Random randomFor(const std::string &type, const std::string &check) {
    return Random(uint32_t(std::hash<std::string>{}(type + "/" + check)));
}

int registerLensConformanceTests(const LensSubject &subject, std::function<std::vector<LensSubject>()> partners) {
    const std::string suite = "LensConformance/" + subject.name;
    int registered = 0;
    for (const ConformanceCheck &check : conformanceChecks()) {
        ::testing::RegisterTest(suite.c_str(), check.name.c_str(), nullptr, nullptr, __FILE__, __LINE__,
                                [&check, subject, partners]() -> ::testing::Test * {
                                    return new ConformanceTest(check, subject, partners);
                                });
        ++registered;
    }
    return registered;
}

namespace {

LensSubject registeredSubject(const LensRegistry &registry, const std::string &type) {
    return {type, [&registry, type] { return registry.create(type); }};
}

std::vector<LensSubject> registeredSubjects(const LensRegistry &registry) {
    std::vector<LensSubject> subjects;
    for (const std::string &type : registry.lensTypes()) subjects.push_back(registeredSubject(registry, type));
    return subjects;
}

} // namespace

int registerLensConformanceTests(const LensRegistry &registry) {
    int registered = 0;
    for (const std::string &type : registry.lensTypes())
        registered += registerLensConformanceTests(registeredSubject(registry, type),
                                                   [&registry] { return registeredSubjects(registry); });
    return registered;
}

int registerStaticLensConformanceTests(const MvclLensPluginEntry *entry) {
    // One registry per entry, alive until exit: the tests run after this returns.
    static std::vector<std::unique_ptr<LensRegistry>> registries;
    registries.push_back(std::make_unique<LensRegistry>());
    registries.back()->add(entry);
    return registerLensConformanceTests(*registries.back());
}

} // namespace mvcl::test
