#pragma once
/// \file LensRegistry_p.h
/// Private to LensRegistry: the registered entries and the loaded modules they came from.

#include <mvcl/lens/LensPlugin.h>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>

namespace mvcl {

/// One dlopen'ed plugin module. Shared by the registration and by every lens it made, so the
/// module's code stays mapped until the last of them is gone; the destructor dlclose()s it.
class LensPluginModule {
public:
    LensPluginModule(void *handle, std::filesystem::path path);
    ~LensPluginModule();
    LensPluginModule(const LensPluginModule &) = delete;
    LensPluginModule &operator=(const LensPluginModule &) = delete;

    void *handle() const { return m_handle; }
    const std::filesystem::path &path() const { return m_path; }

private:
    void *m_handle;
    std::filesystem::path m_path;
};

class LensRegistryPrivate {
public:
    struct Registration {
        const MvclLensPluginEntry *entry = nullptr;
        std::string origin;                       ///< module path or "static"
        std::shared_ptr<LensPluginModule> module; ///< null for statically linked plugins
    };

    /// Checks `entry` (ABI version first, then sizes, build tag, name, factory), creates one
    /// lens as a trial (so a plugin whose create() throws or whose lens misnames itself is
    /// refused at load time, not when a user first asks for it) and registers it. Throws
    /// mvcl::Error("plugin <origin>", problem) and leaves the registry unchanged.
    void add(const MvclLensPluginEntry *entry, const std::string &origin,
             std::shared_ptr<LensPluginModule> module);

    /// A new lens from `registration`, committed on its defaults; throws mvcl::Error.
    static std::shared_ptr<Lens> createLens(const Registration &registration);

    /// Keyed by type name; std::less<> so lookups take a string_view.
    std::map<std::string, Registration, std::less<>> types;
};

} // namespace mvcl
