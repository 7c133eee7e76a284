#pragma once
/// \file PhongTerms.h
/// The metallic-roughness → Phong/Whitted mapping, shared by the glTF loader (factors) and the
/// integrator (textured values per hit). docs/gltf-loading.md shows it on a metallic × roughness
/// grid.

#include <mvcl/core/Export.h>

#include <glm/vec3.hpp>

namespace mvcl {

/// The Phong and Whitted terms of one surface point (see Material for their meaning).
struct PhongTerms {
    glm::vec3 ambient{0.f};
    glm::vec3 diffuse{0.f};
    float specular = 0.f;
    glm::vec3 specularColor{1.f};
    float shininess = 1.f;
    float reflectivity = 0.f;
};

/// With base colour b (linear RGB), metallic m and roughness r (each clamped to [0, 1]):
///   diffuse P      = b · (1 − m)                   metals have no diffuse lobe
///   ambient A      = b · (1 − m·(1 − r))           what is not mirrored scatters the ambient light
///   specular Ks    = mix(0.04 + 0.26·(1 − r), 1, m) dielectrics: 4 % Fresnel floor, stronger when smooth
///   colour S       = mix(white, b, m)              metals tint highlights and reflections
///   shininess Ps   = clamp(2 / max(r, 0.05)⁴ − 2, 1, 1024)   Blinn-Phong exponent of roughness r
///   reflectivity   = m · (1 − r)                   smooth metals mirror the scene and background
/// A rough metal keeps a broad highlight (Ps → 1) of its base colour, so a lit surface is never
/// black unless its base colour is black and it is a rough metal in the dark.
MVCL_EXPORT PhongTerms phongFromMetallicRoughness(glm::vec3 baseColor, float metallic, float roughness);

} // namespace mvcl
