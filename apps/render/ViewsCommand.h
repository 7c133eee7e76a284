#pragma once
// mvcl-render and session files of several views: --view N picks one, --view all renders every
// view side by side in one image; a view in compare mode renders its two stacks split by the
// divider.

#include "RenderCommandLine.h"

#include <mvcl/io/SessionFile.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/view/Framebuffer.h>
#include <mvcl/view/RenderSession.h>

#include <optional>

namespace mvcl {
class LensRegistry;
struct ViewRequest;
} // namespace mvcl

namespace mvcl::cli {

/// The session's view index --view names (0 without --view); throws Error("command line")
/// for a value that is neither a number nor "all".
int sessionViewOf(const RenderCommandLine &cl);

/// Gives the session the view's stack, or its two stacks and divider in compare mode.
void setViewStacks(RenderSession &session, const LensStack &lenses, const std::optional<CompareDescription> &compare);

/// The lens outlines drawn over `image`: in compare mode each stack's only on its side.
void drawViewOutlines(const LensStack &lenses, const std::optional<CompareDescription> &compare, Framebuffer &image);

/// --view all: loads the scene once, renders every view of the session file at the command
/// line's size, and writes them side by side (view 0 leftmost). Returns the exit code.
int renderAllViews(const RenderCommandLine &cl, const LensRegistry &registry, const ViewRequest &request);

} // namespace mvcl::cli
