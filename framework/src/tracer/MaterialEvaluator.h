#pragma once
// Private to the tracer: a material's Phong/Whitted terms at one hit, with its textures sampled
// (base colour, metallic-roughness, normal, occlusion, emission), alpha masks and blending. The
// integrator shades with what evaluate() returns and asks isCutOut()/transmittance() about hits
// that alpha may remove.

#include <mvcl/model/PhongTerms.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/SurfaceInteraction.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace mvcl {

struct Material;
struct Scene;
struct TextureRef;
struct TriangleMesh;
enum class TextureColorSpace : uint8_t;

namespace detail {

/// What shading needs of the material at one hit.
struct ShadedSurface {
    PhongTerms phong;
    float transparency = 0.f;
    float ior = 1.5f;
    glm::vec3 emission{0.f};
    /// The shading normal, perturbed by a normal map; on the side of si.geometricNormal.
    glm::vec3 shadingNormal{0.f, 0.f, 1.f};
};

class MaterialEvaluator {
public:
    explicit MaterialEvaluator(const Scene &scene);

    /// Terms at `hit` seen along `direction` with a ray-cone footprint `coneWidth` wide.
    /// Inline: most hits take their material's stored terms, a copy, and the call's own set-up
    /// for the textured case cost them as much again.
    ShadedSurface evaluate(const Hit &hit, const SurfaceInteraction &si, const glm::vec3 &direction,
                           float coneWidth) const {
        const PlainTerms &plain = m_plainTerms[si.material];
        ShadedSurface s = plain.surface;
        s.shadingNormal = si.shadingNormal;
        if (plain.textured && hit.kind == GeometryKind::Triangle) applyTextures(hit, si, direction, coneWidth, s);
        return s;
    }
    /// True if the hit does not exist because its alpha is below the mask cutoff.
    bool isCutOut(const Hit &hit) const;
    /// Share of light a shadow ray keeps through this hit (1 where cut out).
    float transmittance(const Hit &hit) const;

private:
    /// evaluate() on a triangle of a metallic-roughness material: its textures' values.
    void applyTextures(const Hit &hit, const SurfaceInteraction &si, const glm::vec3 &direction, float coneWidth,
                       ShadedSurface &s) const;
    const Material &materialOf(const Hit &hit) const;
    /// Alpha (factor × base colour texture) at a triangle hit, finest level.
    float alphaAt(const Hit &hit, const Material &m) const;
    /// Interpolated texture coordinates of the set `ref` uses, transformed; false without them.
    bool texcoords(const Hit &hit, const TextureRef &ref, glm::vec2 &uv) const;
    /// log2 of the footprint in level-0 texels of `ref`'s texture (ray cones).
    float levelOfDetail(const Hit &hit, const TextureRef &ref, const glm::vec3 &direction,
                        const glm::vec3 &geometricNormal, float coneWidth) const;
    glm::vec4 sample(const Hit &hit, const TextureRef &ref, TextureColorSpace space, const glm::vec3 &direction,
                     const glm::vec3 &geometricNormal, float coneWidth, bool &found) const;

    const Scene &m_scene;
    /// Per material, the terms of an untextured hit (the shading normal left to the hit): one
    /// copy of a whole ShadedSurface per hit instead of seventeen floats one by one.
    struct PlainTerms {
        ShadedSurface surface;
        bool textured = false; ///< Material::hasMetallicRoughness: triangle hits sample textures
    };
    std::vector<PlainTerms> m_plainTerms;
};

} // namespace detail
} // namespace mvcl
