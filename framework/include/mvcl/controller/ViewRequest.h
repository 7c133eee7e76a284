#pragma once
/// \file ViewRequest.h
/// What a user asks a view to show, before anything is read: a scene, a session (lens-stack)
/// file, extra lenses, layer rules and camera choices. mvcl-render fills it from its command
/// line; an interactive viewer from its command line or an open dialog. ViewSetup turns it
/// into a scene to load and a camera, by the same rules for every app.

#include <mvcl/io/SceneLoader.h>

#include <glm/vec3.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mvcl {

struct ViewRequest {
    /// Model path or builtin:NAME; empty = the scene the session file names.
    std::string source;
    /// Further model files, layered inside `source` in this order (several files as layers:
    /// loadScene(std::span)). Used only with `source`.
    std::vector<std::string> moreSources;
    /// Lens-stack (session) file: lenses, and the scene, camera and layer rules unless given
    /// here. Empty = none.
    std::filesystem::path sessionFile;
    /// Which view of a session file of several views is this view: its camera, visible layers
    /// and lenses (0 = the first; a Document makes one view of each).
    int sessionView = 0;
    /// One lens each, "type:key=value,..." (parseLensSpec), stacked above the file's lenses.
    std::vector<std::string> lensSpecs;
    /// How to load the scene. Its layer rules are the user's: they come before the session
    /// file's, and the first matching rule wins, so these win.
    SceneLoadOptions loadOptions;
    /// A camera of the scene by name or index; wins over the session file's camera.
    std::string sceneCamera;
    /// Parts of the chosen view to override, in world space (the file's units).
    std::optional<glm::vec3> eye;
    std::optional<glm::vec3> target;
    std::optional<glm::vec3> up;
    std::optional<float> verticalFovDegrees;
    /// Names this request in errors about its own values (a bad lens spec, an unknown
    /// sceneCamera, no scene): the app's command line by default. mvcl-render exits 2 for it.
    std::string origin = "command line";
};

} // namespace mvcl
