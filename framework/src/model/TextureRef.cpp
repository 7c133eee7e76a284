#include <mvcl/model/TextureRef.h>

#include <cmath>

namespace mvcl {

glm::vec2 TextureRef::transform(glm::vec2 uv) const {
    if (rotation == 0.f) return offset + scale * uv;
    // KHR_texture_transform: translation · rotation · scale, its rotation matrix
    // [cos sin; −sin cos] (counter-clockwise in uv with v pointing down).
    const float c = std::cos(rotation), s = std::sin(rotation);
    const glm::vec2 p = scale * uv;
    return offset + glm::vec2(c * p.x + s * p.y, -s * p.x + c * p.y);
}

} // namespace mvcl
