#pragma once
/// \file AnimationFile.h
/// Animation files: JSON, read against the lens stack they animate, so that every lens named
/// and every property keyed is checked before a frame renders. docs/animation.md has the format;
/// in short:
///
///     { "version": 1, "duration": 2, "frameRate": 30,
///       "camera": {"keyframes": [{"time": 0, "eye": [6, 4, 8], "fov": 40, "easing": "smooth"}],
///                  "orbit": {"axis": [0, 1, 0], "angles": [0, 360]}},
///       "lenses": [{"lens": "reveal",            // a label, or an index (0 = bottom)
///                   "keyframes": [{"time": 0, "properties": {"distance": 0},
///                                  "region": {"center": [0.3, 0.5]}},
///                                 {"time": 2, "properties": {"distance": 4}}]}] }
///
/// Unknown keys, a lens the stack does not have, an unknown property, a value out of its
/// declared range, a time outside [0, duration] or keyframes out of time order are errors
/// naming the file and the JSON path ("anim.json: lenses[0].keyframes[1].time: ...").

#include <mvcl/core/Export.h>

#include <mvcl/io/Animation.h>
#include <mvcl/lens/LensStack.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace mvcl {

/// Reads and checks an animation of `lenses`. Throws mvcl::Error(path, "json.path: problem").
MVCL_EXPORT Animation readAnimationFile(const std::filesystem::path &path, const LensStack &lenses);
/// The same from text; errors name `sourceName` in place of a file.
MVCL_EXPORT Animation parseAnimationJson(std::string_view text, const std::string &sourceName,
                                         const LensStack &lenses);

/// The file's text; lenses are named by their label when no other lens of `lenses` has it, else
/// by index.
MVCL_EXPORT std::string animationJson(const Animation &animation, const LensStack &lenses);
/// Writes atomically (a temporary file beside it, then rename). Throws mvcl::Error(path, problem).
MVCL_EXPORT void writeAnimationFile(const std::filesystem::path &path, const Animation &animation,
                                    const LensStack &lenses);

/// Adds a sweep given on the command line to `animation` (Animation::addSweep): "LENS.PROPERTY=FROM:TO"
/// where LENS is a label or an index of `lenses` and FROM, TO are values in the property's text
/// form ("reveal.distance=0:4", "1.tint=1,0,0:0,0,1"). Throws mvcl::Error("--sweep", problem).
MVCL_EXPORT void addSweepSpec(Animation &animation, std::string_view spec, const LensStack &lenses);

} // namespace mvcl
