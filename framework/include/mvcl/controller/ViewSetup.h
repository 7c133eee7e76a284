#pragma once
/// \file ViewSetup.h
/// How every app sets up a view from a ViewRequest, shared by mvcl-render and the viewer:
///
/// 1. prepare(): read the session file (its view request.sessionView), stack the request's lenses above the file's, pick the
///    scene (the request's, else the file's) and merge the layer rules (the request's first,
///    so they win over the file's);
/// 2. the app loads the scene: loadScene(setup.sources(), setup.loadOptions);
/// 3. camera(): the request's scene camera, else the session file's camera (a scene camera by
///    name or an explicit look-at in world units), else a built-in scene's own view, else a
///    framing of the whole scene; then the request's eye/target/up/fov override parts of it;
/// 4. describe(): the effective session (scene, world camera, merged rules, visible layers,
///    lenses) for saving, in the session-file format.

#include <mvcl/core/Export.h>

#include <mvcl/controller/ViewRequest.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/LoadedScene.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/io/SessionFile.h>
#include <mvcl/view/Camera.h>

#include <optional>
#include <filesystem>
#include <string>
#include <vector>

namespace mvcl {

class LensRegistry;

struct MVCL_EXPORT ViewSetup {
    /// The scene to load: model path or builtin:NAME (a relative path in a session file comes
    /// resolved against the file's folder).
    std::string source;
    /// Further model files layered inside `source` (the request's, else the session file's).
    std::vector<std::string> moreSources;
    /// The request's load options with the merged layer rules (the request's first, then the
    /// session file's).
    SceneLoadOptions loadOptions;
    /// The session file as read (or empty), with the request's lenses on top; its camera is
    /// still in world units or names a scene camera.
    LensStackDescription session;
    /// The whole session file as read (all its views, links and layout), when one was named.
    std::optional<SessionDescription> sessionFile;

    /// `source` followed by `moreSources`: what loadScene reads.
    std::vector<std::string> sources() const;

    /// Steps 1: reads the session file and parses the lens specs, without loading the scene.
    /// Throws mvcl::Error(sessionFile, problem) for a bad file and mvcl::Error(request.origin,
    /// problem) for a bad lens spec or when no scene is named anywhere.
    static ViewSetup prepare(const ViewRequest &request, const LensRegistry &registry);

    /// Step 3: the view's camera in scene space for a view of `aspect` (width / height).
    /// Throws mvcl::Error naming the request's origin or the session file when a named scene
    /// camera does not exist.
    Camera camera(const Scene &scene, const ViewRequest &request, float aspect) const;

    /// Step 4: the session as a file would hold it: this setup's scene and merged rules,
    /// `camera` (scene space) in world units, the visible layers and the lenses given.
    LensStackDescription describe(const Scene &scene, const Camera &camera, const LensStack &lenses,
                                  uint32_t visibleLayers) const;
    /// The same with the session's own lenses and visible layers.
    LensStackDescription describe(const Scene &scene, const Camera &camera) const;

    /// The same scene as `other` would load: the same files (two names of one file count as
    /// one), layer rules and contact tolerance. Loading a session keeps the scene then.
    bool loadsSameScene(const ViewSetup &other) const;
    /// The request with which a running app opens session file `file`: the app's way of loading
    /// (`options`: default lights, inference) with the file's layer rules and contact tolerance.
    static ViewRequest sessionFileRequest(const std::filesystem::path &file, const SceneLoadOptions &options);
    /// This setup's scene and its tracer (one BVH); a load error is said to be the error of the
    /// scene of `sessionFile`.
    LoadedScene loadSessionScene(const std::filesystem::path &sessionFile) const;
    /// Gives `scene`'s layers the session's names ("layerNames") over their own; names of
    /// layers the scene does not have are left out. Only names change: a tracer of the scene
    /// stays valid.
    void renameLayers(Scene &scene) const;

    /// The field of view a framed view uses when nobody gives one.
    static constexpr float kDefaultVerticalFovDegrees = 40.f;
};

} // namespace mvcl
