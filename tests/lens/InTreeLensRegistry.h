#pragma once
// The lens types of the in-tree plugin modules, as the test binary finds them through
// LensRegistry::defaultSearchPath() (build/lib/mvcl/plugins next to build/bin), loaded once.

#include <mvcl/core/Error.h>
#include <mvcl/lens/LensRegistry.h>

#include <vector>

namespace mvcl::test {

struct InTreeLensRegistry {
    LensRegistry registry;
    std::vector<Error> loadErrors;
    InTreeLensRegistry() : loadErrors(registry.loadModules(LensRegistry::defaultSearchPath())) {}
};

inline const InTreeLensRegistry &inTreeLenses() {
    static const InTreeLensRegistry lenses;
    return lenses;
}

} // namespace mvcl::test
