#pragma once
/// \file ModelFormat_p.h
/// Which reader a model file goes to: its extension says what the user expects, its first
/// bytes what it holds. SceneLoader trusts the content when it is recognisable.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mvcl::detail {

enum class ModelFormat : uint8_t { Gltf, Obj, Stl, Ply };

std::optional<ModelFormat> modelFormatFromExtension(std::string_view extension);
/// `head` is the file's first bytes (a kilobyte or more), `size` its whole size.
std::optional<ModelFormat> modelFormatFromContent(std::span<const std::uint8_t> head, std::uint64_t size);
/// A phrase for well-known files that are not models ("a PNG image"); empty otherwise.
std::string otherFileKind(std::span<const std::uint8_t> head);
const char *modelFormatName(ModelFormat format);

} // namespace mvcl::detail
