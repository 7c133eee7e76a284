#pragma once
/// \file LensPlugin.h
/// The plugin ABI. A lens plugin is one source file that ends with
///
///     MVCL_LENS_PLUGIN(MyLens, kMyLensInfo)
///
/// Built as a module (mvcl_add_lens_plugin in CMake) this defines the extern "C" entry point
/// `mvcl_lens_plugin`, which returns a plain struct the loader checks — ABI version first,
/// then struct sizes and the build tag — before it reads anything else. Built with
/// MVCL_LENS_STATIC_ID=<id> defined, the entry is named `mvcl_lens_plugin_<id>` instead and is
/// registered explicitly with LensRegistry::add (no static-initialiser tricks).

#include <mvcl/lens/Lens.h>

#include <cstdint>

/// Bump on any change to MvclLensPluginEntry, Lens, LensInfo or LensContribution layout.
#define MVCL_LENS_ABI_VERSION 2u

/// Compiler and standard library the plugin was built with: C++ objects (std::string in
/// LensInfo, std::shared_ptr) cross the boundary, so both sides must agree.
#if defined(_GLIBCXX_RELEASE)
#define MVCL_LENS_BUILD_TAG "libstdc++-" MVCL_LENS_STRINGIFY(_GLIBCXX_RELEASE) "/c++20"
#elif defined(_LIBCPP_VERSION)
#define MVCL_LENS_BUILD_TAG "libc++-" MVCL_LENS_STRINGIFY(_LIBCPP_VERSION) "/c++20"
#else
#define MVCL_LENS_BUILD_TAG "unknown/c++20"
#endif
#define MVCL_LENS_STRINGIFY_(x) #x
#define MVCL_LENS_STRINGIFY(x) MVCL_LENS_STRINGIFY_(x)

extern "C" {

/// What a plugin module exports. Only append fields; the first one never moves.
struct MvclLensPluginEntry {
    uint32_t abiVersion;       ///< MVCL_LENS_ABI_VERSION the plugin was built against
    uint32_t entrySize;        ///< sizeof(MvclLensPluginEntry)
    uint32_t lensSize;         ///< sizeof(mvcl::Lens)
    uint32_t infoSize;         ///< sizeof(mvcl::LensInfo)
    uint32_t contributionSize; ///< sizeof(mvcl::LensContribution)
    const char *buildTag;      ///< MVCL_LENS_BUILD_TAG
    const char *name;          ///< lens type name (LensInfo::name)
    const char *description;   ///< LensInfo::description
    mvcl::Lens *(*create)();   ///< a new lens on its defaults, uncommitted
    void (*destroy)(mvcl::Lens *);
};

using MvclLensPluginEntryFunction = const MvclLensPluginEntry *(*)();
}

/// Symbol the loader looks up in a plugin module.
#define MVCL_LENS_PLUGIN_SYMBOL "mvcl_lens_plugin"

#if defined(MVCL_LENS_STATIC_ID)
#define MVCL_LENS_ENTRY_NAME_(id) mvcl_lens_plugin_##id
#define MVCL_LENS_ENTRY_NAME(id) MVCL_LENS_ENTRY_NAME_(id)
#define MVCL_LENS_ENTRY MVCL_LENS_ENTRY_NAME(MVCL_LENS_STATIC_ID)
#define MVCL_LENS_EXPORT
#else
#define MVCL_LENS_ENTRY mvcl_lens_plugin
#define MVCL_LENS_EXPORT __attribute__((visibility("default")))
#endif

/// Defines the plugin's entry point for `LensClass` (default-constructible, derived from
/// mvcl::Lens) described by `info` (a const mvcl::LensInfo with static storage).
#define MVCL_LENS_PLUGIN(LensClass, info)                                                       \
    extern "C" MVCL_LENS_EXPORT const MvclLensPluginEntry *MVCL_LENS_ENTRY() {                  \
        static const MvclLensPluginEntry entry{                                                 \
            MVCL_LENS_ABI_VERSION,                                                              \
            uint32_t(sizeof(MvclLensPluginEntry)),                                              \
            uint32_t(sizeof(mvcl::Lens)),                                                       \
            uint32_t(sizeof(mvcl::LensInfo)),                                                   \
            uint32_t(sizeof(mvcl::LensContribution)),                                           \
            MVCL_LENS_BUILD_TAG,                                                                \
            (info).name.c_str(),                                                                \
            (info).description.c_str(),                                                         \
            []() -> mvcl::Lens * { return new LensClass(); },                                   \
            [](mvcl::Lens *lens) { delete lens; },                                              \
        };                                                                                      \
        return &entry;                                                                          \
    }
