#include <mvcl/model/LayerTable.h>

#include <mvcl/core/Error.h>

#include <algorithm>
#include <string>

namespace mvcl {

namespace {
// Distinct, readable colours for false-colour views; cycles past eight layers.
glm::vec3 defaultLayerColor(int id) {
    static const glm::vec3 kPalette[] = {
        {0.90f, 0.75f, 0.60f}, {0.85f, 0.30f, 0.25f}, {0.30f, 0.60f, 0.90f}, {0.40f, 0.80f, 0.40f},
        {0.95f, 0.80f, 0.20f}, {0.70f, 0.40f, 0.85f}, {0.25f, 0.80f, 0.80f}, {0.95f, 0.55f, 0.15f},
    };
    return kPalette[id % 8];
}
} // namespace

Layer &LayerTable::ensure(int id) {
    if (id < 0 || id >= kMaxLayers)
        throw Error("", "layer " + std::to_string(id) + " is out of range 0.." +
                            std::to_string(kMaxLayers - 1));
    auto it = std::lower_bound(m_layers.begin(), m_layers.end(), id,
                               [](const Layer &l, int v) { return l.id < v; });
    if (it != m_layers.end() && it->id == id) return *it;
    Layer layer;
    layer.id = id;
    layer.name = "layer " + std::to_string(id);
    layer.color = defaultLayerColor(id);
    return *m_layers.insert(it, std::move(layer));
}

const Layer *LayerTable::find(int id) const {
    auto it = std::lower_bound(m_layers.begin(), m_layers.end(), id,
                               [](const Layer &l, int v) { return l.id < v; });
    return (it != m_layers.end() && it->id == id) ? &*it : nullptr;
}

} // namespace mvcl
