#pragma once
/// \file Material.h
/// A Phong material as in Ortiz et al. (2007), eq. 1:
///   colour = E + A + I·(P·(L·N) + Ks·S·(N·H)^Ps) / D
/// plus the Whitted terms: mirror reflectivity (tinted by S) and transparency with an index of
/// refraction. Materials that come from glTF keep their metallic-roughness parameters and texture
/// references too, so that textures can vary the Phong terms per hit (MetallicRoughness.h).

#include <mvcl/core/Export.h>

#include <mvcl/model/TextureRef.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

namespace mvcl {

/// How a material's alpha (base colour alpha × texture alpha) is used, as glTF's alphaMode.
enum class AlphaMode : uint8_t {
    Opaque, ///< alpha is ignored
    Mask,   ///< a hit with alpha < alphaCutoff does not exist (for every ray, shadow rays too)
    Blend,  ///< 1 − alpha adds to the transparency
};

/// The glTF metallic-roughness description a Material was derived from.
struct MetallicRoughness {
    /// Linear RGB base colour factor, 0..1, and its alpha.
    glm::vec3 baseColor{1.f};
    float alpha = 1.f;
    float metallic = 1.f;
    float roughness = 1.f;
    TextureRef baseColorTexture;         ///< sRGB; rgb × baseColor, a × alpha
    TextureRef metallicRoughnessTexture; ///< linear; b × metallic, g × roughness
    TextureRef normalTexture;            ///< tangent space; strength = normalTexture.scale
    TextureRef occlusionTexture;         ///< linear r; scales the ambient term by strength
    TextureRef emissiveTexture;          ///< sRGB; × emission
};

struct MVCL_EXPORT Material {
    std::string name;
    /// A: ambient reflectance, multiplied by the scene's ambient light. Linear RGB, 0..1.
    glm::vec3 ambient{0.8f};
    /// P: diffuse reflectance (albedo). Linear RGB, 0..1.
    glm::vec3 diffuse{0.8f};
    /// Ks: specular coefficient, 0..1.
    float specular = 0.f;
    /// S: colour of highlights and of the mirror reflection: white for dielectrics, the base
    /// colour for metals. Linear RGB, 0..1.
    glm::vec3 specularColor{1.f};
    /// Ps: Phong exponent of (N·H), ≥ 1.
    float shininess = 32.f;
    /// Weight of the mirror-reflected ray, 0..1 (tinted by specularColor).
    float reflectivity = 0.f;
    /// Weight of the refracted ray, 0..1; the rest of the surface colour is scaled by (1 − it).
    float transparency = 0.f;
    /// Index of refraction of the inside of the surface (outside is vacuum), ≥ 1.
    float ior = 1.5f;
    /// E: emitted radiance, linear RGB ≥ 0, added whatever the lights.
    glm::vec3 emission{0.f};

    AlphaMode alphaMode = AlphaMode::Opaque;
    /// Mask threshold (AlphaMode::Mask).
    float alphaCutoff = 0.5f;
    /// glTF doubleSided, recorded for display. Both sides are always shaded: lenses cut into
    /// closed meshes and must show their inside.
    bool doubleSided = false;

    /// Set for materials derived from glTF metallic-roughness; the Phong terms above are those of
    /// the factors, and a hit on a textured material recomputes them from the textured values.
    bool hasMetallicRoughness = false;
    MetallicRoughness metallicRoughness;

    /// True if some hit on this material may be transparent (transparency, or BLEND alpha).
    bool mayTransmit() const;
    /// True if some hit on this material may be cut out (MASK alpha below the cutoff).
    bool mayCutOut() const;
};

} // namespace mvcl
