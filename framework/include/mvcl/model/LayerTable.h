#pragma once
/// \file LayerTable.h
/// The layers of a scene: 0 is the outermost (skin, housing), higher ids lie deeper inside.
/// A ray's layer mask has bit `id` set for each layer it may hit, so there are at most 32.

#include <mvcl/core/Export.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mvcl {

inline constexpr int kMaxLayers = 32;
inline constexpr uint32_t kAllLayers = 0xffffffffu;

/// Mask of the single layer `id`.
constexpr uint32_t layerBit(int id) { return 1u << uint32_t(id); }
/// Mask of layers `first` and everything deeper ("from layer k inward").
constexpr uint32_t layersFrom(int first) {
    return first <= 0 ? kAllLayers : (first >= kMaxLayers ? 0u : kAllLayers << uint32_t(first));
}

struct Layer {
    int id = 0;
    std::string name;
    /// Display colour (false-colour views, UI swatches), linear RGB.
    glm::vec3 color{1.f};
};

class MVCL_EXPORT LayerTable {
public:
    /// Returns the layer with `id`, adding it (with a generated name and colour) if missing.
    /// Throws mvcl::Error if id is outside [0, kMaxLayers).
    Layer &ensure(int id);
    const Layer *find(int id) const;
    const std::vector<Layer> &layers() const { return m_layers; }
    int count() const { return int(m_layers.size()); }

private:
    std::vector<Layer> m_layers; // sorted by id
};

} // namespace mvcl
