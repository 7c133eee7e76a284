#pragma once
// Private to the io module: the one-view schema of LensStackFile.cpp, which the session file
// (SessionFile.cpp) reuses for the scene part and for each of its views.

#include "JsonFile_p.h"

#include <mvcl/io/LensStackFile.h>

#include <filesystem>

namespace mvcl::detail {

/// A version-1 document (or a part of a version-2 one with the same keys) read at `where`.
LensStackDescription readDescription(const Json &document, const LensRegistry &registry, const JsonLocation &where);
/// The version-1 document, keys in the order files have always had.
Json descriptionJson(const LensStackDescription &description);
/// A model file, as opposed to builtin:NAME; its path in a file is relative to the file.
bool isSceneFile(const std::string &scene);
/// Relative model paths read from `file` made relative to the working folder, and back.
void resolveScenePaths(LensStackDescription &description, const std::filesystem::path &file);
void relocateScenePaths(LensStackDescription &description, const std::filesystem::path &file);

} // namespace mvcl::detail
