// The test tint lens (TestLenses.h) as a plugin source, linked statically into mvcl_tests with
// mvcl_add_static_lens(... tint ...): LensConformanceTest runs the suite on it through
// MVCL_LENS_CONFORMANCE_TESTS(tint), as an out-of-tree plugin's test binary does.

#include "TestLenses.h"

#include <mvcl/lens/LensPlugin.h>

MVCL_LENS_PLUGIN(mvcl::test::TintLens, mvcl::test::TintLens::typeInfo())
