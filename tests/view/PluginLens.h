#pragma once
// Committed lenses of the in-tree plugin types (layer, magnifier, …), loaded once from the
// build tree's plugin folder, for the view tests (picking, depth histogram).

#include <mvcl/lens/LensRegistry.h>

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>

namespace mvcl::test {

struct InTreePlugins {
    LensRegistry registry;
    InTreePlugins() {
        for (const char *type : {"layer", "achromatic", "shadow", "magnifier"})
            registry.loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / ("mvcl-lens-" + std::string(type) + ".so"));
    }
};

inline const LensRegistry &inTreePluginRegistry() {
    static const InTreePlugins plugins;
    return plugins.registry;
}

/// A lens of an in-tree `type` over `region` with `properties` (name, text), committed.
inline std::shared_ptr<Lens> pluginLens(const std::string &type, const LensRegion &region,
                                        std::initializer_list<std::pair<const char *, const char *>> properties = {}) {
    std::shared_ptr<Lens> lens = inTreePluginRegistry().create(type);
    for (const auto &[name, text] : properties) lens->setPropertyText(name, text);
    lens->setRegion(region);
    lens->commit();
    return lens;
}

} // namespace mvcl::test
