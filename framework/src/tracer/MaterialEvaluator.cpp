#include "MaterialEvaluator.h"

#include <mvcl/model/Scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mvcl::detail {

namespace {

/// Below this |cos| between ray and surface the footprint stops growing (grazing hits would
/// otherwise pick the 1×1 level).
constexpr float kMinFootprintCosine = 0.05f;

} // namespace

MaterialEvaluator::MaterialEvaluator(const Scene &scene) : m_scene(scene) {
    m_plainTerms.reserve(scene.materials.size());
    for (const Material &m : scene.materials) {
        PlainTerms &plain = m_plainTerms.emplace_back();
        plain.textured = m.hasMetallicRoughness;
        ShadedSurface &s = plain.surface;
        s.phong.ambient = m.ambient;
        s.phong.diffuse = m.diffuse;
        s.phong.specular = m.specular;
        s.phong.specularColor = m.specularColor;
        s.phong.shininess = m.shininess;
        s.phong.reflectivity = m.reflectivity;
        s.transparency = m.transparency;
        s.ior = m.ior;
        s.emission = m.emission;
    }
}

const Material &MaterialEvaluator::materialOf(const Hit &hit) const {
    switch (hit.kind) {
    case GeometryKind::Triangle: return m_scene.materials[m_scene.meshes[hit.geometry].material];
    case GeometryKind::Sphere: return m_scene.materials[m_scene.spheres[hit.geometry].material];
    case GeometryKind::Plane: return m_scene.materials[m_scene.planes[hit.geometry].material];
    }
    return m_scene.materials.front();
}

bool MaterialEvaluator::texcoords(const Hit &hit, const TextureRef &ref, glm::vec2 &uv) const {
    if (hit.kind != GeometryKind::Triangle || !ref.isSet() || std::size_t(ref.texture) >= m_scene.textures.size())
        return false;
    const TriangleMesh &mesh = m_scene.meshes[hit.geometry];
    const std::vector<glm::vec2> &set = ref.texCoord == 1 ? mesh.texcoords1 : mesh.texcoords0;
    if (set.size() != mesh.positions.size()) return false;
    const glm::uvec3 tri = mesh.indices[hit.primitive];
    const float b1 = hit.u, b2 = hit.v, b0 = 1.f - b1 - b2;
    uv = ref.transform(b0 * set[tri.x] + b1 * set[tri.y] + b2 * set[tri.z]);
    return true;
}

float MaterialEvaluator::levelOfDetail(const Hit &hit, const TextureRef &ref, const glm::vec3 &direction,
                                       const glm::vec3 &geometricNormal, float coneWidth) const {
    if (!(coneWidth > 0.f)) return 0.f;
    const TriangleMesh &mesh = m_scene.meshes[hit.geometry];
    const std::vector<glm::vec2> &set = ref.texCoord == 1 ? mesh.texcoords1 : mesh.texcoords0;
    const glm::uvec3 tri = mesh.indices[hit.primitive];
    const Texture &texture = m_scene.textures[std::size_t(ref.texture)];
    if (!texture.image) return 0.f;
    // Texels per unit of surface: sqrt(texel area / world area) of the triangle.
    const glm::vec2 t1 = (set[tri.y] - set[tri.x]) * ref.scale, t2 = (set[tri.z] - set[tri.x]) * ref.scale;
    const float texelArea = std::abs(t1.x * t2.y - t1.y * t2.x) * float(texture.image->width()) *
                            float(texture.image->height());
    const float worldArea = glm::length(glm::cross(mesh.positions[tri.y] - mesh.positions[tri.x],
                                                   mesh.positions[tri.z] - mesh.positions[tri.x]));
    if (!(texelArea > 0.f) || !(worldArea > 0.f)) return 0.f;
    const float cosine = std::max(std::abs(glm::dot(direction, geometricNormal)), kMinFootprintCosine);
    const float footprint = coneWidth * std::sqrt(texelArea / worldArea) / cosine;
    return std::isfinite(footprint) && footprint > 0.f ? std::log2(footprint) : 0.f;
}

glm::vec4 MaterialEvaluator::sample(const Hit &hit, const TextureRef &ref, TextureColorSpace space,
                                    const glm::vec3 &direction, const glm::vec3 &geometricNormal, float coneWidth,
                                    bool &found) const {
    glm::vec2 uv;
    found = texcoords(hit, ref, uv);
    if (!found) return glm::vec4(1.f);
    const float lod = levelOfDetail(hit, ref, direction, geometricNormal, coneWidth);
    return m_scene.textures[std::size_t(ref.texture)].sample(uv, lod, space);
}

float MaterialEvaluator::alphaAt(const Hit &hit, const Material &m) const {
    const TextureRef &ref = m.metallicRoughness.baseColorTexture;
    float alpha = m.metallicRoughness.alpha;
    glm::vec2 uv;
    if (texcoords(hit, ref, uv))
        alpha *= m_scene.textures[std::size_t(ref.texture)].sample(uv, 0.f, TextureColorSpace::Linear).a;
    return alpha;
}

bool MaterialEvaluator::isCutOut(const Hit &hit) const {
    const Material &m = materialOf(hit);
    if (m.alphaMode != AlphaMode::Mask) return false;
    return !(alphaAt(hit, m) >= m.alphaCutoff);
}

float MaterialEvaluator::transmittance(const Hit &hit) const {
    const Material &m = materialOf(hit);
    if (m.alphaMode == AlphaMode::Mask && !(alphaAt(hit, m) >= m.alphaCutoff)) return 1.f;
    float transparency = std::clamp(m.transparency, 0.f, 1.f);
    if (m.alphaMode == AlphaMode::Blend && m.metallicRoughness.baseColorTexture.isSet())
        transparency = std::max(transparency, std::clamp(1.f - alphaAt(hit, m), 0.f, 1.f));
    return transparency;
}

void MaterialEvaluator::applyTextures(const Hit &hit, const SurfaceInteraction &si, const glm::vec3 &direction,
                                      float coneWidth, ShadedSurface &s) const {
    const Material &m = m_scene.materials[si.material];

    const MetallicRoughness &mr = m.metallicRoughness;
    const glm::vec3 &ng = si.geometricNormal;
    bool found = false;
    glm::vec3 base = mr.baseColor;
    float alpha = mr.alpha, metallic = mr.metallic, roughness = mr.roughness;
    bool remap = false;
    if (mr.baseColorTexture.isSet()) {
        const glm::vec4 t = sample(hit, mr.baseColorTexture, TextureColorSpace::Srgb, direction, ng, coneWidth, found);
        if (found) {
            base *= glm::vec3(t);
            alpha *= t.a;
            remap = true;
        }
    }
    if (mr.metallicRoughnessTexture.isSet()) {
        const glm::vec4 t =
            sample(hit, mr.metallicRoughnessTexture, TextureColorSpace::Linear, direction, ng, coneWidth, found);
        if (found) {
            roughness *= t.g;
            metallic *= t.b;
            remap = true;
        }
    }
    if (remap) s.phong = phongFromMetallicRoughness(base, metallic, roughness);
    if (m.alphaMode == AlphaMode::Blend && mr.baseColorTexture.isSet())
        s.transparency = std::max(s.transparency, std::clamp(1.f - alpha, 0.f, 1.f));
    if (mr.occlusionTexture.isSet()) {
        const glm::vec4 t = sample(hit, mr.occlusionTexture, TextureColorSpace::Linear, direction, ng, coneWidth, found);
        if (found) s.phong.ambient *= 1.f + std::clamp(mr.occlusionTexture.strength, 0.f, 1.f) * (t.r - 1.f);
    }
    if (mr.emissiveTexture.isSet()) {
        const glm::vec4 t = sample(hit, mr.emissiveTexture, TextureColorSpace::Srgb, direction, ng, coneWidth, found);
        if (found) s.emission *= glm::vec3(t);
    }
    if (mr.normalTexture.isSet()) {
        const TriangleMesh &mesh = m_scene.meshes[hit.geometry];
        if (mesh.tangents.size() == mesh.positions.size()) {
            const glm::vec4 t =
                sample(hit, mr.normalTexture, TextureColorSpace::Linear, direction, ng, coneWidth, found);
            if (found) {
                const glm::uvec3 tri = mesh.indices[hit.primitive];
                const float b1 = hit.u, b2 = hit.v, b0 = 1.f - b1 - b2;
                const glm::vec4 tw = b0 * mesh.tangents[tri.x] + b1 * mesh.tangents[tri.y] + b2 * mesh.tangents[tri.z];
                const glm::vec3 n = si.shadingNormal;
                // Gram-Schmidt: the interpolated tangent made perpendicular to the shading normal.
                glm::vec3 tangent = glm::vec3(tw) - glm::dot(glm::vec3(tw), n) * n;
                const float len = glm::length(tangent);
                if (len > 1e-8f && std::isfinite(len)) {
                    tangent /= len;
                    const glm::vec3 bitangent = (tw.w < 0.f ? -1.f : 1.f) * glm::cross(n, tangent);
                    const float scale = mr.normalTexture.strength;
                    const glm::vec3 local((2.f * t.x - 1.f) * scale, (2.f * t.y - 1.f) * scale, 2.f * t.z - 1.f);
                    const glm::vec3 perturbed = local.x * tangent + local.y * bitangent + local.z * n;
                    const float plen = glm::length(perturbed);
                    if (plen > 0.f && std::isfinite(plen)) {
                        s.shadingNormal = perturbed / plen;
                        // Never past the geometric horizon: shading there would light the back.
                        if (glm::dot(s.shadingNormal, ng) <= 0.f) s.shadingNormal = n;
                    }
                }
            }
        }
    }
}

} // namespace mvcl::detail
