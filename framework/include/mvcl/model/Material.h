#pragma once
/// \file Material.h
/// A Phong material as in Ortiz et al. (2007), eq. 1:
///   colour = A + I·(P·(L·N) + Ks·(N·H)^Ps) / D
/// plus the Whitted terms: mirror reflectivity and transparency with an index of refraction.

#include <glm/vec3.hpp>

#include <string>

namespace mvcl {

struct Material {
    std::string name;
    /// A: ambient reflectance, multiplied by the scene's ambient light. Linear RGB, 0..1.
    glm::vec3 ambient{0.8f};
    /// P: diffuse reflectance (albedo). Linear RGB, 0..1.
    glm::vec3 diffuse{0.8f};
    /// Ks: specular coefficient, 0..1 (white highlights).
    float specular = 0.f;
    /// Ps: Phong exponent of (N·H), ≥ 1.
    float shininess = 32.f;
    /// Weight of the mirror-reflected ray, 0..1.
    float reflectivity = 0.f;
    /// Weight of the refracted ray, 0..1; the rest of the surface colour is scaled by (1 − it).
    float transparency = 0.f;
    /// Index of refraction of the inside of the surface (outside is vacuum), ≥ 1.
    float ior = 1.5f;
};

} // namespace mvcl
