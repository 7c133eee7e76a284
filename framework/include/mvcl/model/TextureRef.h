#pragma once
/// \file TextureRef.h
/// A material's use of a texture: which one, which texture coordinates, and glTF's
/// KHR_texture_transform.

#include <mvcl/core/Export.h>

#include <glm/vec2.hpp>

namespace mvcl {

struct MVCL_EXPORT TextureRef {
    /// Index into Scene::textures, or −1 for none.
    int texture = -1;
    /// Which TriangleMesh texture coordinates to use: 0 (TEXCOORD_0) or 1 (TEXCOORD_1).
    int texCoord = 0;
    /// normalTexture.scale or occlusionTexture.strength; 1 for the others.
    float strength = 1.f;
    /// KHR_texture_transform: uv' = offset + rotate(rotation) · (scale ⊙ uv).
    glm::vec2 offset{0.f};
    float rotation = 0.f;
    glm::vec2 scale{1.f};

    bool isSet() const { return texture >= 0; }
    glm::vec2 transform(glm::vec2 uv) const;
};

} // namespace mvcl
