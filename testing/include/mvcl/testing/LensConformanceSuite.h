#pragma once
/// \file LensConformanceSuite.h
/// Every check of LensConformance.h as GoogleTest tests, registered per lens type, so that a
/// plugin's own test binary runs the same suite as mvcl's tree and as mvcl-lens-conformance.
/// The tests are named `LensConformance/<lens type>.<check>`, e.g.
/// `LensConformance/invert.DeclaredCommutativityHoldsWhenRendered`, so
/// `--gtest_filter='LensConformance/invert.*'` picks one lens.
///
/// For a lens linked statically (mvcl_add_static_lens(<target> <id> ...) in CMake), one line at
/// namespace scope in any source file of the test binary:
///
///     MVCL_LENS_CONFORMANCE_TESTS(invert)
///
/// For lens types in a registry (plugin modules), or a lens class the test can name:
///
///     registerLensConformanceTests(registry);                        // every type in it
///     registerLensConformanceTests({"tint", [] { return std::make_shared<TintLens>(); }});
///
/// Register before RUN_ALL_TESTS() (in main, or at static initialisation as the macro does).

#include <mvcl/lens/LensPlugin.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/testing/LensConformance.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mvcl::test {

/// One of the suite's checks: its test name and how it runs on a subject (partners are the
/// other lens types its commutativity is checked against).
struct ConformanceCheck {
    std::string name;
    std::function<::testing::AssertionResult(const LensSubject &subject, const std::vector<LensSubject> &partners)>
        run;
};

/// The suite, in the order the tests run.
const std::vector<ConformanceCheck> &conformanceChecks();

/// The random generator a check uses for a lens type: reproducible per type and check, so a
/// failure reruns alone with the same values.
Random randomFor(const std::string &type, const std::string &check);

/// A lens made by `create` committed on its defaults (for a class the test can name).
template <class LensClass> LensFactory committedFactory() {
    return [] {
        auto lens = std::make_shared<LensClass>();
        lens->commit();
        return std::shared_ptr<Lens>(lens);
    };
}

/// Registers the suite for `subject`; `partners` (called when a test runs) lists the lens types
/// that commutativity is checked against; empty means the subject alone. Returns the number of
/// tests registered.
int registerLensConformanceTests(const LensSubject &subject,
                                 std::function<std::vector<LensSubject>()> partners = {});

/// Registers the suite for every lens type of `registry`, each checked for commutativity
/// against all of them. The registry must outlive the tests.
int registerLensConformanceTests(const LensRegistry &registry);

/// Registers the suite for a statically linked plugin's entry (the macro below). The registry
/// holding it lives until the process ends.
int registerStaticLensConformanceTests(const MvclLensPluginEntry *entry);

} // namespace mvcl::test

/// The suite for a lens linked statically with mvcl_add_static_lens(<target> <id> ...): its
/// entry point mvcl_lens_plugin_<id> is declared and registered. Use at global namespace scope.
#define MVCL_LENS_CONFORMANCE_TESTS(id)                                                         \
    extern "C" const MvclLensPluginEntry *mvcl_lens_plugin_##id();                              \
    [[maybe_unused]] static const int mvcl_lens_conformance_tests_##id =                        \
        ::mvcl::test::registerStaticLensConformanceTests(mvcl_lens_plugin_##id())
