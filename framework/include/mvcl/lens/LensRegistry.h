#pragma once
/// \file LensRegistry.h
/// The lens types an app can create: plugin modules found at run time plus plugins linked
/// statically and registered explicitly. A module that is broken or built against another ABI
/// is reported with a clear error and skipped; it never takes the app down.

#include <mvcl/core/Export.h>

#include <mvcl/core/Error.h>
#include <mvcl/lens/Lens.h>

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

struct MvclLensPluginEntry;

namespace mvcl {

class LensRegistryPrivate;

class MVCL_EXPORT LensRegistry {
public:
    LensRegistry();
    ~LensRegistry();
    LensRegistry(const LensRegistry &) = delete;
    LensRegistry &operator=(const LensRegistry &) = delete;

    /// Registers a statically linked plugin's entry. Throws mvcl::Error(origin, problem) on an
    /// ABI mismatch or a type name that is already registered.
    void add(const MvclLensPluginEntry *entry, const std::string &origin = "static");

    /// Loads one plugin module (dlopen) and registers it; throws mvcl::Error(path, problem).
    void loadModule(const std::filesystem::path &path);

    /// Loads every plugin module (files named mvcl-lens-*.so) in `directories`, in order;
    /// directories that do not exist are skipped. A module that fails is skipped and its error
    /// returned; a type found again in a later directory is ignored (first wins).
    std::vector<Error> loadModules(const std::vector<std::filesystem::path> &directories);

    /// Where plugin modules are looked for: every directory in $MVCL_PLUGIN_PATH (':'-separated)
    /// first, then the running executable's directory, then <exe dir>/../lib/mvcl/plugins
    /// (the build tree and the install tree).
    static std::vector<std::filesystem::path> defaultSearchPath();

    /// Sorted type names.
    std::vector<std::string> lensTypes() const;
    bool contains(std::string_view type) const;
    /// Module path or "static" for the type; throws for unknown types.
    std::string origin(std::string_view type) const;

    /// A new lens of `type`, committed on its defaults. The module stays loaded while any lens
    /// it made is alive. Throws mvcl::Error("lens", "unknown lens type 'x' (known: ...)").
    std::shared_ptr<Lens> create(std::string_view type) const;

private:
    std::unique_ptr<LensRegistryPrivate> d;
};

} // namespace mvcl
