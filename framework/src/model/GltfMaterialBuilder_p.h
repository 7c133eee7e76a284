#pragma once
/// \file GltfMaterialBuilder_p.h
/// Private to the glTF loader: glTF materials → mvcl Materials (the metallic-roughness mapping of
/// PhongTerms.h, emission, alpha modes, transmission, ior) and the textures they use → Scene
/// textures (decoded once per image, only when a material refers to them).

#include "GltfContext_p.h"
#include "GltfImageDecoder_p.h"

#include <mvcl/model/GltfLoader.h>

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

namespace mvcl::gltf {

/// Encoded bytes of images given by URI (data URI or external file read through the sandbox),
/// by image index; images in a bufferView are read from the validated buffers instead.
using CapturedImages = std::map<int, std::vector<std::uint8_t>>;

class GltfMaterialBuilder {
public:
    GltfMaterialBuilder(GltfContext &context, const CapturedImages &images, const GltfLoadOptions &options,
                        Scene &scene);

    /// Appends one Material per glTF material (same indices) and the textures they use.
    void build();

    /// The factor part of the mapping (no textures), for one glTF material.
    static Material mapFactors(const tinygltf::Material &material);

private:
    TextureRef textureRef(const tinygltf::TextureInfo &info, const std::string &slot, int material,
                          float strength, TextureColorSpace space);
    TextureRef textureRef(int index, int texCoord, const tinygltf::ExtensionMap &extensions,
                          const std::string &slot, int material, float strength, TextureColorSpace space);
    /// Scene texture index of glTF texture `index`, or −1 (with a warning) if it cannot be used.
    /// `space` is how the first material slot that uses the image reads it (its levels average
    /// in linear light when sRGB).
    int sceneTexture(int index, const std::string &where, TextureColorSpace space);
    std::shared_ptr<const TextureImage> image(int index, const std::string &where, TextureColorSpace space);

    GltfContext &m_context;
    const tinygltf::Model &m_model;
    const CapturedImages &m_captured;
    Scene &m_scene;
    GltfImageDecoder m_decoder;
    std::map<int, int> m_sceneTextures;                                  // glTF texture → Scene::textures
    std::map<int, std::shared_ptr<const TextureImage>> m_images;         // glTF image → decoded (or null)
};

} // namespace mvcl::gltf
