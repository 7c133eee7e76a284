#pragma once
/// \file Texture.h
/// A decoded image with its mip chain (TextureImage) and the sampler a glTF texture reads it with
/// (Texture). Texels are stored as 8-bit RGBA as decoded; sRGB textures (base colour, emission)
/// are turned linear per texel before filtering.

#include <mvcl/core/Export.h>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mvcl {

enum class TextureWrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureFilter : uint8_t { Nearest, Linear };
/// How levels are used when the footprint is larger than a texel.
enum class MipmapMode : uint8_t {
    None,    ///< level 0 only (glTF minFilter NEAREST or LINEAR)
    Nearest, ///< the nearest level
    Linear,  ///< blend of the two nearest levels
};

struct TextureSampler {
    TextureWrap wrapS = TextureWrap::Repeat;
    TextureWrap wrapT = TextureWrap::Repeat;
    TextureFilter magFilter = TextureFilter::Linear;
    TextureFilter minFilter = TextureFilter::Linear;
    MipmapMode mipmapMode = MipmapMode::Linear;
};

enum class TextureColorSpace : uint8_t { Linear, Srgb };

/// An RGBA8 image and its box-filtered mip chain down to 1×1.
class MVCL_EXPORT TextureImage {
public:
    /// `rgba` holds width·height·4 bytes, rows top to bottom (glTF's uv (0, 0) is the top left).
    /// The levels of an sRGB image average in linear light (a distant black-and-white checker
    /// is a mid grey, not the darker sRGB average).
    TextureImage(std::string name, int width, int height, std::vector<std::uint8_t> rgba,
                 TextureColorSpace space = TextureColorSpace::Linear);

    const std::string &name() const { return m_name; }
    int width() const { return m_levels.front().width; }
    int height() const { return m_levels.front().height; }
    int levelCount() const { return int(m_levels.size()); }
    int levelWidth(int level) const { return m_levels[std::size_t(level)].width; }
    int levelHeight(int level) const { return m_levels[std::size_t(level)].height; }
    /// Bytes held by all levels.
    std::size_t memoryBytes() const;

    /// The raw texel (0..1 per channel) at integer coordinates inside the level.
    glm::vec4 texel(int level, int x, int y) const {
        const Level &l = m_levels[std::size_t(level)];
        const std::uint8_t *p = l.rgba.data() + (std::size_t(y) * std::size_t(l.width) + std::size_t(x)) * 4;
        return glm::vec4(p[0], p[1], p[2], p[3]) * (1.f / 255.f);
    }
    /// The texel with rgb turned from sRGB to linear (alpha is always linear).
    glm::vec4 linearTexel(int level, int x, int y) const;

private:
    struct Level {
        int width = 0, height = 0;
        std::vector<std::uint8_t> rgba;
    };
    std::string m_name;
    std::vector<Level> m_levels;
};

/// A texture as a material uses it: an image (shared between textures that differ only in their
/// sampler) and its sampler.
struct MVCL_EXPORT Texture {
    std::string name;
    std::shared_ptr<const TextureImage> image;
    TextureSampler sampler;

    /// Filtered value at uv with the level of detail `lod` (log2 of the footprint in level-0
    /// texels; ≤ 0 magnifies). Linear RGBA; rgb converted from sRGB first when `space` says so.
    glm::vec4 sample(glm::vec2 uv, float lod, TextureColorSpace space) const;
};

} // namespace mvcl
