#include <mvcl/model/Texture.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace mvcl {

namespace {

/// sRGB → linear for every 8-bit value, computed once.
const std::array<float, 256> &srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const float v = float(i) / 255.f;
            t[std::size_t(i)] = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
        }
        return t;
    }();
    return table;
}

/// Integer texel coordinate for `i` in a level of `size` texels under the wrap mode.
int wrapIndex(int i, int size, TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::ClampToEdge: return std::clamp(i, 0, size - 1);
    case TextureWrap::Repeat: {
        const int m = i % size;
        return m < 0 ? m + size : m;
    }
    case TextureWrap::MirroredRepeat: {
        const int period = 2 * size;
        int m = i % period;
        if (m < 0) m += period;
        return m < size ? m : period - 1 - m;
    }
    }
    return 0;
}

/// Texture coordinates far outside [0, 1] would overflow int; wrapping modes only need the
/// fractional part (and the period's parity for mirroring), clamping only [0, 1].
float reduceCoordinate(float u, TextureWrap wrap) {
    if (!std::isfinite(u)) return 0.f;
    if (wrap == TextureWrap::ClampToEdge) return std::clamp(u, -1.f, 2.f);
    return u - 2.f * std::floor(u * 0.5f);
}

/// Linear 0..1 → the nearest 8-bit sRGB code, by binary search in the decoding table (exact
/// inverse of what sampling does).
std::uint8_t linearToSrgb8(float v) {
    const std::array<float, 256> &t = srgbTable();
    const auto it = std::lower_bound(t.begin(), t.end(), v);
    if (it == t.begin()) return 0;
    if (it == t.end()) return 255;
    const auto below = it - 1;
    return std::uint8_t((v - *below < *it - v ? below : it) - t.begin());
}

} // namespace

TextureImage::TextureImage(std::string name, int width, int height, std::vector<std::uint8_t> rgba,
                           TextureColorSpace space)
    : m_name(std::move(name)) {
    const std::array<float, 256> &table = srgbTable();
    const bool srgb = space == TextureColorSpace::Srgb;
    Level base;
    base.width = std::max(width, 1);
    base.height = std::max(height, 1);
    base.rgba = std::move(rgba);
    base.rgba.resize(std::size_t(base.width) * std::size_t(base.height) * 4, 255);
    m_levels.push_back(std::move(base));
    // Box filter: each texel of the next level averages the up to 2×2 texels it covers (odd
    // sizes clamp the last row and column). Averages are of the stored values.
    while (m_levels.back().width > 1 || m_levels.back().height > 1) {
        const Level &src = m_levels.back();
        Level next;
        next.width = std::max(1, src.width / 2);
        next.height = std::max(1, src.height / 2);
        next.rgba.resize(std::size_t(next.width) * std::size_t(next.height) * 4);
        for (int y = 0; y < next.height; ++y)
            for (int x = 0; x < next.width; ++x)
                for (int c = 0; c < 4; ++c) {
                    const bool decode = srgb && c < 3; // alpha is always linear
                    int sum = 0;
                    float linearSum = 0.f;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx) {
                            const int sx = std::min(2 * x + dx, src.width - 1);
                            const int sy = std::min(2 * y + dy, src.height - 1);
                            const std::uint8_t v = src.rgba[(std::size_t(sy) * std::size_t(src.width) +
                                                             std::size_t(sx)) * 4 + std::size_t(c)];
                            sum += v;
                            linearSum += table[v];
                        }
                    next.rgba[(std::size_t(y) * std::size_t(next.width) + std::size_t(x)) * 4 + std::size_t(c)] =
                        decode ? linearToSrgb8(0.25f * linearSum) : std::uint8_t((sum + 2) / 4);
                }
        m_levels.push_back(std::move(next));
    }
}

std::size_t TextureImage::memoryBytes() const {
    std::size_t bytes = 0;
    for (const Level &l : m_levels) bytes += l.rgba.size();
    return bytes;
}

glm::vec4 TextureImage::linearTexel(int level, int x, int y) const {
    const Level &l = m_levels[std::size_t(level)];
    const std::uint8_t *p = l.rgba.data() + (std::size_t(y) * std::size_t(l.width) + std::size_t(x)) * 4;
    const std::array<float, 256> &t = srgbTable();
    return glm::vec4(t[p[0]], t[p[1]], t[p[2]], float(p[3]) * (1.f / 255.f));
}

glm::vec4 Texture::sample(glm::vec2 uv, float lod, TextureColorSpace space) const {
    if (!image) return glm::vec4(1.f);
    const TextureImage &img = *image;
    const auto fetch = [&](int level, int x, int y) {
        return space == TextureColorSpace::Srgb ? img.linearTexel(level, x, y) : img.texel(level, x, y);
    };
    const float u = reduceCoordinate(uv.x, sampler.wrapS);
    const float v = reduceCoordinate(uv.y, sampler.wrapT);
    const auto sampleLevel = [&](int level, TextureFilter filter) {
        const int w = img.levelWidth(level), h = img.levelHeight(level);
        const float x = u * float(w), y = v * float(h);
        if (filter == TextureFilter::Nearest)
            return fetch(level, wrapIndex(int(std::floor(x)), w, sampler.wrapS),
                         wrapIndex(int(std::floor(y)), h, sampler.wrapT));
        // Bilinear between the four texel centres around (x, y).
        const float fx = x - 0.5f, fy = y - 0.5f;
        const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
        const float tx = fx - float(x0), ty = fy - float(y0);
        const int xa = wrapIndex(x0, w, sampler.wrapS), xb = wrapIndex(x0 + 1, w, sampler.wrapS);
        const int ya = wrapIndex(y0, h, sampler.wrapT), yb = wrapIndex(y0 + 1, h, sampler.wrapT);
        const glm::vec4 top = glm::mix(fetch(level, xa, ya), fetch(level, xb, ya), tx);
        const glm::vec4 bottom = glm::mix(fetch(level, xa, yb), fetch(level, xb, yb), tx);
        return glm::mix(top, bottom, ty);
    };
    if (!(lod > 0.f) || sampler.mipmapMode == MipmapMode::None)
        return sampleLevel(0, lod > 0.f ? sampler.minFilter : sampler.magFilter);
    const float maxLevel = float(img.levelCount() - 1);
    const float level = std::min(lod, maxLevel);
    if (sampler.mipmapMode == MipmapMode::Nearest)
        return sampleLevel(int(std::lround(level)), sampler.minFilter);
    const int lower = int(std::floor(level));
    const float t = level - float(lower);
    const glm::vec4 a = sampleLevel(lower, sampler.minFilter);
    if (t <= 0.f || lower + 1 > int(maxLevel)) return a;
    return glm::mix(a, sampleLevel(lower + 1, sampler.minFilter), t);
}

} // namespace mvcl
