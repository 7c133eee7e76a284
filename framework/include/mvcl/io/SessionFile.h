#pragma once
/// \file SessionFile.h
/// Session files of several views: one scene, N views (each a camera, visible layers, a lens
/// stack and optionally a compare stack with its divider), the links between views and the
/// layout they are shown in.
///
///     { "version": 2,
///       "scene": "body.glb", "layerRules": [...], "layerContact": {...}, "memoryBudgetMiB": 512,
///       "views": [ {"camera": {...}, "visibleLayers": "1-", "lenses": [...],
///                   "compare": {"divider": 0.5, "lenses": [...]}},
///                  {"camera": {...}, "lenses": [...]} ],
///       "links": [{"views": [0, 1], "camera": true, "lenses": false, "layers": true}],
///       "layout": "1x2", "focus": 0 }
///
/// A view's keys read as a version-1 file's (LensStackFile.h). A file without "version" or
/// with version 1 is one view, read as ever; in version 2 the one-view keys "camera",
/// "visibleLayers" and "lenses" at the top level are an error, as is any unknown key.
///
/// Writing: a session of one view with no compare stack, no links and layout "1" is written as
/// version 1, byte for byte as lensStackJson writes it, so the files of one-view sessions stay
/// readable by builds that predate several views. Anything more is written as version 2.

#include <mvcl/core/Export.h>

#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/ViewLayout.h>
#include <mvcl/io/ViewLink.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mvcl {

/// The right-hand stack of a view in compare mode and where the divider stands.
struct CompareDescription {
    float divider = 0.5f; ///< normalised x of the divider, 0..1
    LensStack lenses;     ///< right of the divider (the view's own stack is left of it)
};

struct SessionViewDescription {
    std::optional<LensStackCamera> camera;
    uint32_t visibleLayers = kAllLayers;
    LensStack lenses;
    std::optional<CompareDescription> compare;
};

struct MVCL_EXPORT SessionDescription {
    /// The scene part: scene files, layer rules, contact, memory budget. Its camera, visible
    /// layers and lenses are not used (each view has its own).
    LensStackDescription common;
    std::vector<SessionViewDescription> views; ///< at least one
    std::vector<ViewLink> links;
    ViewLayout layout = ViewLayout::Single;
    int focus = 0; ///< the focused view

    /// View `index` (clamped to the views) as a one-view file holds it: the scene part and
    /// that view's camera, visible layers and lenses.
    LensStackDescription view(int index) const;
    /// A one-view session from a one-view file.
    static SessionDescription fromView(const LensStackDescription &description);
    /// Written as version 1 (see the file comment).
    bool isSingleView() const;
};

/// Reads a session file of any version; relative scene paths come back resolved against the
/// file's folder. Throws mvcl::Error(path, "json.path: problem"), also for links that name a
/// view that does not exist and a focus outside the views.
MVCL_EXPORT SessionDescription readSessionFile(const std::filesystem::path &path, const LensRegistry &registry);
/// The same from text; errors name `sourceName`.
MVCL_EXPORT SessionDescription parseSessionJson(std::string_view text, const std::string &sourceName,
                                                const LensRegistry &registry);
/// The file's text (version 1 when isSingleView()).
MVCL_EXPORT std::string sessionJson(const SessionDescription &description);
/// Writes atomically, scene paths relative to the file's folder. Throws mvcl::Error(path, problem).
MVCL_EXPORT void writeSessionFile(const std::filesystem::path &path, const SessionDescription &description);

} // namespace mvcl
