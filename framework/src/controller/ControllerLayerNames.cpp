// Controller: layers renamed by the user, over the names the scene came with. The scene is
// shared (by the views of a document, by render sessions) and stays as loaded: a view keeps its
// renames beside it.

#include "Controller_p.h"

#include <iterator>

namespace mvcl {

void Controller::Private::setLayerNames(std::map<int, std::string> names) {
    layerNames = std::move(names);
    for (auto it = layerNames.begin(); it != layerNames.end();) // names of layers the scene lacks go
        it = scene->layers.find(it->first) ? std::next(it) : layerNames.erase(it);
}

void Controller::setLayerName(int layer, const std::string &name) {
    const std::string source = "layer " + std::to_string(layer);
    if (!d->scene->layers.find(layer))
        throw Error(source, "the scene has no such layer (it has " + std::to_string(d->scene->layers.count()) + ")");
    if (name.find_first_of("\r\n") != std::string::npos) throw Error(source, "a layer name is one line");
    std::map<int, std::string> names = d->layerNames;
    if (name.empty() || d->scene->layers.find(layer)->name == name) names.erase(layer);
    else names[layer] = name;
    d->edit(Private::StepKind::Other, [&] { d->setLayerNames(std::move(names)); });
}

std::string Controller::layerName(int layer) const {
    if (const auto renamed = d->layerNames.find(layer); renamed != d->layerNames.end()) return renamed->second;
    const Layer *found = d->scene->layers.find(layer);
    return found ? found->name : std::string();
}

} // namespace mvcl
