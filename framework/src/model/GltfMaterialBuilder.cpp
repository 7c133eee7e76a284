#include "GltfMaterialBuilder_p.h"

#include <mvcl/model/PhongTerms.h>

#include <algorithm>
#include <cmath>

namespace mvcl::gltf {

namespace {

double numberOr(const tinygltf::Value &v, double fallback) {
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

float clamp01(double v) { return std::isfinite(v) ? float(std::clamp(v, 0.0, 1.0)) : 0.f; }

const tinygltf::Value *extension(const tinygltf::ExtensionMap &map, const char *name) {
    const auto it = map.find(name);
    return it == map.end() ? nullptr : &it->second;
}

TextureWrap wrapOf(int mode) {
    switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
    default: return TextureWrap::Repeat;
    }
}

TextureSampler samplerOf(const tinygltf::Sampler &s) {
    TextureSampler out;
    out.wrapS = wrapOf(s.wrapS);
    out.wrapT = wrapOf(s.wrapT);
    out.magFilter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? TextureFilter::Nearest : TextureFilter::Linear;
    switch (s.minFilter) {
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
        out.minFilter = TextureFilter::Nearest;
        out.mipmapMode = MipmapMode::None;
        break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR:
        out.minFilter = TextureFilter::Linear;
        out.mipmapMode = MipmapMode::None;
        break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
        out.minFilter = TextureFilter::Nearest;
        out.mipmapMode = MipmapMode::Nearest;
        break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
        out.minFilter = TextureFilter::Linear;
        out.mipmapMode = MipmapMode::Nearest;
        break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
        out.minFilter = TextureFilter::Nearest;
        out.mipmapMode = MipmapMode::Linear;
        break;
    default: // LINEAR_MIPMAP_LINEAR, or unspecified: the best filter
        out.minFilter = TextureFilter::Linear;
        out.mipmapMode = MipmapMode::Linear;
        break;
    }
    return out;
}

} // namespace

GltfMaterialBuilder::GltfMaterialBuilder(GltfContext &context, const CapturedImages &images,
                                         const GltfLoadOptions &options, Scene &scene)
    : m_context(context), m_model(context.model()), m_captured(images), m_scene(scene),
      m_decoder(options.maxTexturePixels, options.maxTextureBytes) {}

Material GltfMaterialBuilder::mapFactors(const tinygltf::Material &src) {
    const auto &pbr = src.pbrMetallicRoughness;
    Material m;
    m.name = src.name;
    m.hasMetallicRoughness = true;
    MetallicRoughness &mr = m.metallicRoughness;
    if (pbr.baseColorFactor.size() == 4) {
        mr.baseColor = glm::vec3(clamp01(pbr.baseColorFactor[0]), clamp01(pbr.baseColorFactor[1]),
                                 clamp01(pbr.baseColorFactor[2]));
        mr.alpha = clamp01(pbr.baseColorFactor[3]);
    }
    mr.metallic = clamp01(pbr.metallicFactor);
    mr.roughness = clamp01(pbr.roughnessFactor);
    const PhongTerms t = phongFromMetallicRoughness(mr.baseColor, mr.metallic, mr.roughness);
    m.ambient = t.ambient;
    m.diffuse = t.diffuse;
    m.specular = t.specular;
    m.specularColor = t.specularColor;
    m.shininess = t.shininess;
    m.reflectivity = t.reflectivity;

    if (src.emissiveFactor.size() == 3) {
        double strength = 1.0;
        if (const tinygltf::Value *e = extension(src.extensions, "KHR_materials_emissive_strength"))
            strength = numberOr(e->Get("emissiveStrength"), 1.0);
        if (!std::isfinite(strength) || strength < 0.0) strength = 1.0;
        for (int c = 0; c < 3; ++c) {
            const double v = src.emissiveFactor[std::size_t(c)] * strength;
            m.emission[c] = std::isfinite(v) ? float(std::max(v, 0.0)) : 0.f;
        }
    }

    if (src.alphaMode == "MASK") {
        m.alphaMode = AlphaMode::Mask;
        m.alphaCutoff = std::isfinite(src.alphaCutoff) ? float(std::max(src.alphaCutoff, 0.0)) : 0.5f;
    } else if (src.alphaMode == "BLEND") {
        m.alphaMode = AlphaMode::Blend;
    }
    m.doubleSided = src.doubleSided;

    double transparency = 0.0;
    if (m.alphaMode == AlphaMode::Blend) transparency = 1.0 - mr.alpha;
    const tinygltf::Value *transmission = extension(src.extensions, "KHR_materials_transmission");
    if (transmission)
        transparency = std::max(transparency, double(clamp01(numberOr(transmission->Get("transmissionFactor"), 0.0))));
    m.transparency = float(transparency);

    // Alpha blending is see-through, not refraction: a BLEND material that does not transmit
    // has no interface to bend light (ior 1).
    double ior = m.alphaMode == AlphaMode::Blend && !transmission ? 1.0 : 1.5;
    if (const tinygltf::Value *iorExt = extension(src.extensions, "KHR_materials_ior"))
        ior = numberOr(iorExt->Get("ior"), 1.5);
    // KHR_materials_ior allows 0 ("infinitely thin"); Snell's law needs ≥ 1.
    if (!std::isfinite(ior) || ior < 1.0) ior = 1.0;
    m.ior = float(std::min(ior, 10.0));
    return m;
}

void GltfMaterialBuilder::build() {
    for (std::size_t i = 0; i < m_model.materials.size(); ++i) {
        const tinygltf::Material &src = m_model.materials[i];
        Material m = mapFactors(src);
        const int index = int(i);
        MetallicRoughness &mr = m.metallicRoughness;
        const auto &pbr = src.pbrMetallicRoughness;
        const TextureColorSpace srgb = TextureColorSpace::Srgb, linear = TextureColorSpace::Linear;
        mr.baseColorTexture = textureRef(pbr.baseColorTexture, "baseColorTexture", index, 1.f, srgb);
        mr.metallicRoughnessTexture =
            textureRef(pbr.metallicRoughnessTexture, "metallicRoughnessTexture", index, 1.f, linear);
        mr.emissiveTexture = textureRef(src.emissiveTexture, "emissiveTexture", index, 1.f, srgb);
        const double normalScale = std::isfinite(src.normalTexture.scale) ? src.normalTexture.scale : 1.0;
        mr.normalTexture = textureRef(src.normalTexture.index, src.normalTexture.texCoord, src.normalTexture.extensions,
                                      "normalTexture", index, float(normalScale), linear);
        mr.occlusionTexture =
            textureRef(src.occlusionTexture.index, src.occlusionTexture.texCoord, src.occlusionTexture.extensions,
                       "occlusionTexture", index, clamp01(src.occlusionTexture.strength), linear);
        // An emissive texture with a black factor emits nothing: glTF multiplies them.
        m_scene.materials.push_back(std::move(m));
    }
    m_context.report().textureBytes = m_decoder.bytesUsed();
}

TextureRef GltfMaterialBuilder::textureRef(const tinygltf::TextureInfo &info, const std::string &slot, int material,
                                           float strength, TextureColorSpace space) {
    return textureRef(info.index, info.texCoord, info.extensions, slot, material, strength, space);
}

TextureRef GltfMaterialBuilder::textureRef(int index, int texCoord, const tinygltf::ExtensionMap &extensions,
                                           const std::string &slot, int material, float strength,
                                           TextureColorSpace space) {
    TextureRef ref;
    if (index < 0) return ref;
    const std::string where = "material " + std::to_string(material) +
                              (m_model.materials[std::size_t(material)].name.empty()
                                   ? std::string()
                                   : " '" + m_model.materials[std::size_t(material)].name + "'") +
                              " " + slot;
    ref.texCoord = texCoord;
    ref.strength = strength;
    if (const tinygltf::Value *t = extension(extensions, "KHR_texture_transform")) {
        const tinygltf::Value &offset = t->Get("offset"), &scale = t->Get("scale");
        if (offset.IsArray() && offset.ArrayLen() == 2)
            ref.offset = glm::vec2(float(numberOr(offset.Get(0), 0.0)), float(numberOr(offset.Get(1), 0.0)));
        if (scale.IsArray() && scale.ArrayLen() == 2)
            ref.scale = glm::vec2(float(numberOr(scale.Get(0), 1.0)), float(numberOr(scale.Get(1), 1.0)));
        ref.rotation = float(numberOr(t->Get("rotation"), 0.0));
        if (t->Has("texCoord")) ref.texCoord = int(numberOr(t->Get("texCoord"), double(ref.texCoord)));
        if (!std::isfinite(ref.offset.x) || !std::isfinite(ref.offset.y) || !std::isfinite(ref.scale.x) ||
            !std::isfinite(ref.scale.y) || !std::isfinite(ref.rotation)) {
            m_context.warn(where + ": KHR_texture_transform has non-finite numbers; ignored");
            ref.offset = glm::vec2(0.f);
            ref.scale = glm::vec2(1.f);
            ref.rotation = 0.f;
        }
    }
    if (ref.texCoord != 0 && ref.texCoord != 1) {
        m_context.warn(where + " uses TEXCOORD_" + std::to_string(ref.texCoord) +
                       "; mvcl reads TEXCOORD_0 and TEXCOORD_1 only, so the factor is used");
        return TextureRef{};
    }
    ref.texture = sceneTexture(index, where, space);
    return ref;
}

int GltfMaterialBuilder::sceneTexture(int index, const std::string &where, TextureColorSpace space) {
    if (const auto it = m_sceneTextures.find(index); it != m_sceneTextures.end()) return it->second;
    int result = -1;
    if (std::size_t(index) >= m_model.textures.size()) {
        m_context.warn(where + " refers to texture " + std::to_string(index) + ", which does not exist; the factor is used");
    } else {
        const tinygltf::Texture &src = m_model.textures[std::size_t(index)];
        int source = src.source;
        // A texture whose only image is in a format we lack names it (KTX2/Basis, WebP).
        if (source < 0)
            for (const char *ext : {"KHR_texture_basisu", "EXT_texture_webp", "MSFT_texture_dds"})
                if (extension(src.extensions, ext)) {
                    m_context.warn(where + ": texture " + std::to_string(index) + " has only a " + ext +
                                   " image, which mvcl does not decode; the factor is used");
                    source = -2;
                }
        if (source == -1)
            m_context.warn(where + ": texture " + std::to_string(index) + " has no image; the factor is used");
        std::shared_ptr<const TextureImage> img = source >= 0 ? image(source, where, space) : nullptr;
        if (img) {
            Texture texture;
            texture.name = !src.name.empty() ? src.name : img->name();
            texture.image = std::move(img);
            if (src.sampler >= 0 && std::size_t(src.sampler) < m_model.samplers.size())
                texture.sampler = samplerOf(m_model.samplers[std::size_t(src.sampler)]);
            else if (src.sampler >= 0)
                m_context.warn(where + ": texture " + std::to_string(index) + " refers to sampler " +
                               std::to_string(src.sampler) + ", which does not exist; the default sampler is used");
            result = int(m_scene.textures.size());
            m_scene.textures.push_back(std::move(texture));
        }
    }
    m_sceneTextures[index] = result;
    return result;
}

std::shared_ptr<const TextureImage> GltfMaterialBuilder::image(int index, const std::string &where,
                                                               TextureColorSpace space) {
    if (const auto it = m_images.find(index); it != m_images.end()) return it->second;
    std::shared_ptr<const TextureImage> result;
    std::string name = "image " + std::to_string(index);
    if (std::size_t(index) >= m_model.images.size()) {
        m_context.warn(where + " refers to image " + std::to_string(index) + ", which does not exist; the factor is used");
    } else {
        const tinygltf::Image &img = m_model.images[std::size_t(index)];
        if (!img.name.empty()) name += " '" + img.name + "'";
        else if (!img.uri.empty() && img.uri.rfind("data:", 0) != 0) name += " '" + img.uri + "'";
        std::span<const std::uint8_t> bytes;
        bool haveBytes = false;
        if (img.bufferView >= 0) {
            // Bounds as the validator checks every bufferView; checked again, cheaply, here.
            if (std::size_t(img.bufferView) < m_model.bufferViews.size()) {
                const tinygltf::BufferView &view = m_model.bufferViews[std::size_t(img.bufferView)];
                if (view.buffer >= 0 && std::size_t(view.buffer) < m_model.buffers.size()) {
                    const std::vector<unsigned char> &data = m_model.buffers[std::size_t(view.buffer)].data;
                    if (view.byteOffset <= data.size() && view.byteLength <= data.size() - view.byteOffset) {
                        bytes = std::span<const std::uint8_t>(data.data() + view.byteOffset, view.byteLength);
                        haveBytes = true;
                    }
                }
            }
            if (!haveBytes) m_context.warn(where + ": " + name + " has an unusable bufferView; the factor is used");
        } else if (const auto it = m_captured.find(index); it != m_captured.end()) {
            bytes = it->second;
            haveBytes = true;
        } else {
            m_context.warn(where + ": " + name + " could not be read; the factor is used");
        }
        if (haveBytes) {
            std::string problem;
            result = m_decoder.decode(bytes, name, space, problem);
            if (result)
                ++m_context.report().texturesDecoded;
            else
                m_context.warn(where + ": " + name + " " + problem + "; the factor is used");
        }
    }
    m_images[index] = result;
    return result;
}

} // namespace mvcl::gltf
