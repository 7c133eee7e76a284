// Controller: layers renamed by the user, over the names the scene came with.

#include "Controller_p.h"

namespace mvcl {

void Controller::Private::setLayerNames(std::map<int, std::string> names) {
    layerNames = std::move(names);
    for (const auto &[id, name] : sceneLayerNames) {
        const auto renamed = layerNames.find(id);
        scene->layers.ensure(id).name = renamed != layerNames.end() ? renamed->second : name;
    }
}

void Controller::setLayerName(int layer, const std::string &name) {
    const std::string source = "layer " + std::to_string(layer);
    if (!d->scene->layers.find(layer))
        throw Error(source, "the scene has no such layer (it has " + std::to_string(d->scene->layers.count()) + ")");
    if (name.find_first_of("\r\n") != std::string::npos) throw Error(source, "a layer name is one line");
    std::map<int, std::string> names = d->layerNames;
    const auto original = d->sceneLayerNames.find(layer);
    if (name.empty() || (original != d->sceneLayerNames.end() && original->second == name)) names.erase(layer);
    else names[layer] = name;
    d->edit(Private::StepKind::Other, [&] { d->setLayerNames(std::move(names)); });
}

std::string Controller::layerName(int layer) const {
    const Layer *found = d->scene->layers.find(layer);
    return found ? found->name : std::string();
}

} // namespace mvcl
