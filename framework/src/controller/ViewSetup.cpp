#include <mvcl/controller/ViewSetup.h>

#include <mvcl/controller/ViewCoordinates.h>
#include <mvcl/core/Error.h>
#include <mvcl/lens/LensRegistry.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace mvcl {

namespace {

/// The scene's camera named `name` (by name or index), or nullptr.
const CameraDesc *findSceneCamera(const Scene &scene, const std::string &name) {
    const CameraDesc *found = nullptr;
    for (std::size_t i = 0; i < scene.cameras.size(); ++i)
        if (scene.cameras[i].name == name || std::to_string(i) == name) found = &scene.cameras[i];
    return found;
}

/// The same scene source: equal text, or two names of one model file.
bool sameSource(const std::string &a, const std::string &b) {
    if (a == b) return true;
    if (a.starts_with("builtin:") || b.starts_with("builtin:")) return false;
    std::error_code ec;
    return std::filesystem::equivalent(a, b, ec);
}

} // namespace

bool ViewSetup::loadsSameScene(const ViewSetup &other) const {
    const auto sameRule = [](const LayerRule &x, const LayerRule &y) {
        return x.pattern == y.pattern && x.layer == y.layer && x.name == y.name;
    };
    return std::ranges::equal(sources(), other.sources(), sameSource) &&
           std::ranges::equal(loadOptions.layerRules.rules(), other.loadOptions.layerRules.rules(), sameRule) &&
           loadOptions.layerContact == other.loadOptions.layerContact;
}

std::vector<std::string> ViewSetup::sources() const {
    std::vector<std::string> all{source};
    all.insert(all.end(), moreSources.begin(), moreSources.end());
    return all;
}

ViewSetup ViewSetup::prepare(const ViewRequest &request, const LensRegistry &registry) {
    ViewSetup setup;
    if (!request.sessionFile.empty()) {
        setup.sessionFile = readSessionFile(request.sessionFile, registry);
        const int views = int(setup.sessionFile->views.size());
        if (request.sessionView < 0 || request.sessionView >= views)
            throw Error(request.origin, "view " + std::to_string(request.sessionView) + " of " +
                                            request.sessionFile.string() + ": the file has " + std::to_string(views) +
                                            (views == 1 ? " view (0)" : " views (0.." + std::to_string(views - 1) + ")"));
        setup.session = setup.sessionFile->view(request.sessionView);
    }
    for (const std::string &spec : request.lensSpecs) {
        try { // a malformed value of the request is the request's error, not the file's
            setup.session.lenses.add(parseLensSpec(spec, registry));
        } catch (const Error &e) {
            throw Error(request.origin, e.what());
        }
    }
    setup.source = request.source.empty() ? setup.session.scene : request.source;
    setup.moreSources = request.source.empty() ? setup.session.moreScenes : request.moreSources;
    if (setup.source.empty())
        throw Error(request.origin, request.sessionFile.empty()
                                        ? std::string("no scene given")
                                        : "no scene given, and " + request.sessionFile.string() + " names none");
    setup.loadOptions = request.loadOptions;
    // The file's rules come last: the first matching rule wins, so the request's win.
    for (const LayerRule &rule : setup.session.layerRules.rules()) setup.loadOptions.layerRules.add(rule);
    // The request's contact tolerance wins over the file's, as its rules do.
    if (!setup.loadOptions.layerContact.isEnabled()) setup.loadOptions.layerContact = setup.session.layerContact;
    // And its memory budget.
    if (setup.loadOptions.memoryBudgetBytes == 0) setup.loadOptions.memoryBudgetBytes = setup.session.memoryBudgetBytes;
    return setup;
}

Camera ViewSetup::camera(const Scene &scene, const ViewRequest &request, float aspect) const {
    const ViewCoordinates coordinates({1, 1}, scene);
    const std::optional<LensStackCamera> &fileCamera = session.camera;
    const bool fileNamesCamera = request.sceneCamera.empty() && fileCamera && !fileCamera->sceneCamera.empty();
    const std::string &cameraName = fileNamesCamera ? fileCamera->sceneCamera : request.sceneCamera;
    Camera camera;
    if (!cameraName.empty()) {
        const CameraDesc *found = findSceneCamera(scene, cameraName);
        if (!found)
            throw Error(fileNamesCamera ? request.sessionFile.string() : request.origin,
                        std::string(fileNamesCamera ? "camera" : "--camera") + " '" + cameraName + "': the scene has " +
                            std::to_string(scene.cameras.size()) + " cameras and none by that name or index");
        camera = Camera::fromDesc(*found);
    } else if (fileCamera) {
        camera = coordinates.cameraFromWorld(*fileCamera);
    } else if (scene.name.rfind("builtin:", 0) == 0 && !scene.cameras.empty()) {
        camera = Camera::fromDesc(scene.cameras.front());
    } else {
        camera = Camera::framing(scene.bounds(), request.verticalFovDegrees.value_or(kDefaultVerticalFovDegrees),
                                 aspect);
    }
    // Explicit values override parts of the chosen view; they are in world space.
    const glm::vec3 eye = request.eye ? coordinates.sceneFromWorld(*request.eye) : camera.eye();
    const glm::vec3 target = request.target ? coordinates.sceneFromWorld(*request.target) : camera.target();
    return Camera::lookAt(eye, target, request.up.value_or(camera.up()),
                          request.verticalFovDegrees.value_or(camera.verticalFovDegrees()));
}

LensStackDescription ViewSetup::describe(const Scene &scene, const Camera &camera, const LensStack &lenses,
                                         uint32_t visibleLayers) const {
    LensStackDescription description;
    description.scene = source;
    description.moreScenes = moreSources;
    description.camera = ViewCoordinates({1, 1}, scene).worldFromCamera(camera);
    description.layerRules = loadOptions.layerRules;
    description.visibleLayers = visibleLayers;
    description.layerContact = loadOptions.layerContact;
    description.memoryBudgetBytes = loadOptions.memoryBudgetBytes;
    description.lenses = lenses; // shares the lenses
    return description;
}

LensStackDescription ViewSetup::describe(const Scene &scene, const Camera &camera) const {
    LensStackDescription description = describe(scene, camera, session.lenses, session.visibleLayers);
    description.layerNames = session.layerNames;
    return description;
}

void ViewSetup::renameLayers(Scene &scene) const {
    for (const auto &[id, name] : session.layerNames)
        if (scene.layers.find(id)) scene.layers.ensure(id).name = name;
}

ViewRequest ViewSetup::sessionFileRequest(const std::filesystem::path &file, const SceneLoadOptions &options) {
    ViewRequest request;
    request.sessionFile = file;
    request.origin = file.string(); // "no scene given" is the file's problem here
    request.loadOptions = options;
    request.loadOptions.layerRules = {};
    request.loadOptions.layerContact = {};
    return request;
}

LoadedScene ViewSetup::loadSessionScene(const std::filesystem::path &sessionFile) const {
    try {
        return LoadedScene::load(sources(), loadOptions);
    } catch (const Error &e) {
        throw Error(sessionFile.string(), "scene: " + std::string(e.what()));
    }
}

} // namespace mvcl
