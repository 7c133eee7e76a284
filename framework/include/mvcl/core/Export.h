#pragma once
/// \file Export.h
/// MVCL_EXPORT marks what libmvcl.so exports: the public classes and functions of these
/// headers. The library is built with hidden visibility, so everything else (the tracer's
/// internals, the glTF reader, the JSON and glTF libraries it is built from) stays inside it
/// and cannot clash with another copy of those libraries in the same process. On ELF the same
/// attribute serves the library and its users, so nothing is defined differently per side.
///
/// One token on the class or function declaration:
///
///     class MVCL_EXPORT Tracer { ... };
///     MVCL_EXPORT Scene loadScene(std::string_view source, const SceneLoadOptions &options = {});
///
/// A class nested in an exported class is exported with it; MVCL_HIDDEN on the declaration of
/// a private implementation keeps it inside (`struct MVCL_HIDDEN Private;`).

#if defined(__GNUC__) || defined(__clang__)
#define MVCL_EXPORT __attribute__((visibility("default")))
#define MVCL_HIDDEN __attribute__((visibility("hidden")))
#else
#define MVCL_EXPORT
#define MVCL_HIDDEN
#endif
