#include <mvcl/lens/LensRegistry.h>

#include "LensRegistry_p.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <set>
#include <system_error>

namespace mvcl {

namespace fs = std::filesystem;

namespace {

std::string pluginSource(const std::string &origin) { return "plugin " + origin; }

/// Compares one field of a plugin's entry with this build's value.
void requireEqual(const std::string &origin, const char *what, uint64_t plugin, uint64_t ours) {
    if (plugin != ours)
        throw Error(pluginSource(origin), std::string("built with ") + what + " " +
                                              std::to_string(plugin) + ", this mvcl has " +
                                              std::to_string(ours) + " (rebuild the plugin)");
}

/// dlerror() text without the "<path>: " prefix glibc puts in front (the error names it).
std::string loaderMessage(const fs::path &path) {
    const char *text = dlerror();
    std::string message = text ? text : "unknown dynamic loader error";
    const std::string prefix = path.string() + ": ";
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    return message;
}

/// One name per file or directory however it was reached (links, "..", relative paths).
fs::path canonicalName(const fs::path &path) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(path, ec);
    return ec ? fs::absolute(path, ec).lexically_normal() : canonical;
}

bool isPluginFileName(const fs::path &path) {
    const std::string name = path.filename().string();
    return name.rfind("mvcl-lens-", 0) == 0 && path.extension() == ".so";
}

/// Destroys a lens with its own module's `destroy` (it was allocated there) and only then lets
/// go of the module, so its code is still mapped while the destructor runs.
struct PluginLensDeleter {
    void (*destroy)(Lens *);
    std::shared_ptr<LensPluginModule> module;

    void operator()(Lens *lens) const noexcept {
        try {
            destroy(lens);
        } catch (...) {
            // A throwing destructor in a plugin must not terminate the app.
        }
    }
};

} // namespace

LensPluginModule::LensPluginModule(void *handle, fs::path path)
    : m_handle(handle), m_path(std::move(path)) {}

LensPluginModule::~LensPluginModule() { dlclose(m_handle); }

void LensRegistryPrivate::add(const MvclLensPluginEntry *entry, const std::string &origin,
                              std::shared_ptr<LensPluginModule> module) {
    const std::string source = pluginSource(origin);
    if (!entry) throw Error(source, "the entry point returned no plugin description");
    // The ABI version is the one field whose position never changes: check it before reading
    // anything else, since the rest of the struct may be laid out differently.
    if (entry->abiVersion != MVCL_LENS_ABI_VERSION)
        throw Error(source, "built for lens ABI " + std::to_string(entry->abiVersion) +
                                ", this mvcl has " + std::to_string(MVCL_LENS_ABI_VERSION));
    requireEqual(origin, "sizeof(MvclLensPluginEntry)", entry->entrySize, sizeof(MvclLensPluginEntry));
    requireEqual(origin, "sizeof(mvcl::Lens)", entry->lensSize, sizeof(Lens));
    requireEqual(origin, "sizeof(mvcl::LensInfo)", entry->infoSize, sizeof(LensInfo));
    requireEqual(origin, "sizeof(mvcl::LensContribution)", entry->contributionSize,
                 sizeof(LensContribution));
    if (!entry->buildTag || std::strcmp(entry->buildTag, MVCL_LENS_BUILD_TAG) != 0)
        throw Error(source, std::string("built with ") +
                                (entry->buildTag ? entry->buildTag : "no build tag") +
                                ", this mvcl with " + MVCL_LENS_BUILD_TAG +
                                " (C++ objects cross the plugin boundary; rebuild the plugin)");
    if (!entry->name || !*entry->name) throw Error(source, "the plugin has no lens type name");
    if (!entry->create || !entry->destroy)
        throw Error(source, std::string("lens '") + entry->name + "' has no create/destroy function");
    if (const auto found = types.find(entry->name); found != types.end())
        throw Error(source, std::string("lens type '") + entry->name + "' is already registered from " +
                                found->second.origin + "; this one is ignored");
    Registration registration{entry, origin, std::move(module)};
    createLens(registration); // the trial lens is destroyed right away
    types.emplace(entry->name, std::move(registration));
}

std::shared_ptr<Lens> LensRegistryPrivate::createLens(const Registration &registration) {
    const MvclLensPluginEntry &entry = *registration.entry;
    const std::string source = pluginSource(registration.origin);
    const std::string type = entry.name;

    Lens *raw = nullptr;
    try {
        raw = entry.create();
    } catch (const std::exception &e) {
        throw Error(source, "creating lens '" + type + "' failed: " + e.what());
    } catch (...) {
        throw Error(source, "creating lens '" + type + "' failed with an unknown exception");
    }
    if (!raw) throw Error(source, "creating lens '" + type + "' returned no lens");
    std::shared_ptr<Lens> lens(raw, PluginLensDeleter{entry.destroy, registration.module});

    if (lens->typeName() != type)
        throw Error(source, "the plugin registers lens type '" + type + "' but its lens calls itself '" +
                                lens->typeName() + "'");
    // A plugin whose contribution fails on its defaults still gives a lens, disabled, with its
    // fault(): files that name it keep it, and apps say why it shows nothing.
    try {
        lens->commitOrDisable();
    } catch (const std::exception &e) {
        throw Error(source, "lens '" + type + "' does not commit on its defaults: " + e.what());
    }
    return lens;
}

LensRegistry::LensRegistry() : d(std::make_unique<LensRegistryPrivate>()) {}

LensRegistry::~LensRegistry() = default;

void LensRegistry::add(const MvclLensPluginEntry *entry, const std::string &origin) {
    d->add(entry, origin, nullptr);
}

void LensRegistry::loadModule(const fs::path &path) {
    const std::string origin = path.string();
    const std::string source = pluginSource(origin);
    // Absolute, because dlopen() looks a name without a '/' up in the library search path.
    std::error_code ec;
    const fs::path file = fs::absolute(path, ec);
    dlerror(); // clear a stale message
    void *handle = ec ? nullptr : dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw Error(source, "cannot be loaded: " + (ec ? ec.message() : loaderMessage(file)));
    // From here on the module is closed again when `module` goes out of scope unregistered.
    auto module = std::make_shared<LensPluginModule>(handle, file);

    dlerror();
    void *symbol = dlsym(handle, MVCL_LENS_PLUGIN_SYMBOL);
    if (!symbol)
        throw Error(source, "no entry point '" MVCL_LENS_PLUGIN_SYMBOL
                            "' (not an mvcl lens plugin, or its source does not end with "
                            "MVCL_LENS_PLUGIN(...))");
    const auto entryFunction = reinterpret_cast<MvclLensPluginEntryFunction>(symbol);
    const MvclLensPluginEntry *entry = nullptr;
    try {
        entry = entryFunction();
    } catch (const std::exception &e) {
        throw Error(source, std::string("the entry point threw: ") + e.what());
    } catch (...) {
        throw Error(source, "the entry point threw an unknown exception");
    }
    d->add(entry, origin, std::move(module));
}

std::vector<Error> LensRegistry::loadModules(const std::vector<fs::path> &directories) {
    std::vector<Error> errors;
    std::set<fs::path> seenDirectories;
    std::set<fs::path> loadedFiles; // the same file reached twice is not a duplicate type
    for (const auto &[type, registration] : d->types)
        if (registration.module) loadedFiles.insert(canonicalName(registration.module->path()));

    for (const fs::path &directory : directories) {
        std::error_code ec;
        if (!fs::is_directory(directory, ec)) continue;
        if (!seenDirectories.insert(canonicalName(directory)).second) continue;

        std::vector<fs::path> files;
        fs::directory_iterator it(directory, ec), end;
        for (; !ec && it != end; it.increment(ec)) {
            std::error_code statusError; // a dangling link is skipped, not a listing error
            if (isPluginFileName(it->path()) && it->is_regular_file(statusError))
                files.push_back(it->path());
        }
        if (ec) {
            errors.emplace_back(directory.string(), "cannot list plugin directory: " + ec.message());
            continue;
        }
        std::sort(files.begin(), files.end());
        for (const fs::path &file : files) {
            if (!loadedFiles.insert(canonicalName(file)).second) continue;
            try {
                loadModule(file);
            } catch (const Error &e) {
                errors.push_back(e);
            }
        }
    }
    return errors;
}

std::vector<fs::path> LensRegistry::defaultSearchPath() {
    std::vector<fs::path> directories;
    if (const char *variable = std::getenv("MVCL_PLUGIN_PATH")) {
        const std::string text = variable;
        std::size_t start = 0;
        while (start <= text.size()) {
            const std::size_t colon = std::min(text.find(':', start), text.size());
            if (colon > start) directories.emplace_back(text.substr(start, colon - start));
            start = colon + 1;
        }
    }
    std::error_code ec;
    const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path executableDir = executable.parent_path();
        directories.push_back(executableDir);
        directories.push_back((executableDir / ".." / "lib" / "mvcl" / "plugins").lexically_normal());
    }
    return directories;
}

std::vector<std::string> LensRegistry::lensTypes() const {
    std::vector<std::string> names;
    for (const auto &[type, registration] : d->types) names.push_back(type);
    return names; // std::map keeps them sorted
}

bool LensRegistry::contains(std::string_view type) const { return d->types.contains(type); }

std::string LensRegistry::origin(std::string_view type) const {
    const auto found = d->types.find(type);
    if (found == d->types.end()) throw Error("lens", "unknown lens type '" + std::string(type) + "'");
    return found->second.origin;
}

std::shared_ptr<Lens> LensRegistry::create(std::string_view type) const {
    const auto found = d->types.find(type);
    if (found == d->types.end()) {
        std::string known;
        for (const auto &[name, registration] : d->types) known += (known.empty() ? "" : ", ") + name;
        throw Error("lens", "unknown lens type '" + std::string(type) + "' (known: " +
                                (known.empty() ? "none; no plugins were found" : known) + ")");
    }
    return LensRegistryPrivate::createLens(found->second);
}

} // namespace mvcl
