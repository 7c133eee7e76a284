#pragma once
// mvcl-render's animation path (--animate, --turntable, --sweep): the animation the command line
// asks for, and its frames rendered by one RenderSession into a FrameWriter.

#include "RenderCommandLine.h"

#include <mvcl/io/Animation.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/model/Scene.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/RenderSession.h>

#include <string>

namespace mvcl::cli {

/// --animate's file read against `lenses`, or the animation --turntable and --sweep make.
/// Throws mvcl::Error (the file's, or "command line" for a bad shortcut or --frames).
Animation commandLineAnimation(const RenderCommandLine &cl, const LensStack &lenses);

/// Renders the frames of `animation` (or --frames A-B) with `session`, whose settings, base
/// policy and lenses are set, from `camera` (scene space), into `output`, and prints what it
/// did. Returns the exit code.
int renderAnimation(const RenderCommandLine &cl, const Animation &animation, RenderSession &session,
                    const LensStack &lenses, const Camera &camera, const Scene &scene, const std::string &output);

} // namespace mvcl::cli
