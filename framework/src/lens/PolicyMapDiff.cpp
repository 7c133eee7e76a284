#include <mvcl/lens/PolicyMapDiff.h>

#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>

#include <algorithm>
#include <bit>
#include <string>
#include <utility>

namespace mvcl {

namespace {

constexpr uint32_t kNoClass = 0xffffffffu;
constexpr int kRowsPerChunk = 16;

// FNV-1a over what PixelPolicy::rendersLike compares, so that policies that render alike hash
// alike: +0 and −0 (equal) hash alike, clip slots past clipCount are left out.
uint64_t renderHash(const PixelPolicy &p) {
    uint64_t hash = 0xcbf29ce484222325ull;
    const auto add = [&hash](uint64_t v) { hash = (hash ^ v) * 0x100000001b3ull; };
    const auto addFloat = [&add](float f) { add(f == 0.f ? 0u : std::bit_cast<uint32_t>(f)); };
    const auto addVec3 = [&addFloat](const glm::vec3 &v) {
        for (int i = 0; i < 3; ++i) addFloat(v[i]);
    };
    const auto addMat3 = [&addVec3](const glm::mat3 &m) {
        for (int c = 0; c < 3; ++c) addVec3(m[c]);
    };
    for (const RayQuery &q : p.ray.visibility) {
        addFloat(q.tMin);
        addFloat(q.tMax);
        add(q.layerMask);
        add(uint64_t(q.clipCount()));
        for (const ClipVolume &clip : q.clips()) {
            add(uint64_t(clip.layerMask()) << 32 | uint64_t(clip.isOriented()) << 24 | uint64_t(clip.capStyle()) << 16 |
                uint64_t(clip.shape()) << 8 | uint64_t(clip.keep()));
            addMat3(clip.boxFromScene());
            addVec3(clip.boxMin()); // also the centre or normal
            addVec3(clip.boxMax());
            addFloat(clip.radius()); // also the offset
        }
    }
    const ShadingPolicy &s = p.ray.shading;
    add(uint64_t(s.shadows) | uint64_t(s.reflections) << 1 | uint64_t(s.refractions) << 2);
    addFloat(s.shadowStrength);
    addVec3(s.shadowTint);
    add(uint32_t(s.maxDepth));
    for (float opacity : s.layerOpacity) addFloat(opacity);
    addFloat(s.edgeOpacity);
    add(uint32_t(s.peelSurfaces));
    add(s.peelLayers);
    add(uint64_t(s.falseColor.mode));
    addFloat(s.falseColor.depthNear);
    addFloat(s.falseColor.depthFar);
    add(uint64_t(s.edges.mode));
    addVec3(s.edges.color);
    addFloat(s.edges.widthPixels);
    addFloat(s.edges.creaseDegrees);
    addMat3(p.ray.color.matrix);
    addVec3(p.ray.color.offset);
    addMat3(p.sampleFromScreen);
    return hash;
}

/// For each of `policies`, the smallest index of a `reference` policy that renders like it,
/// or kNoClass. Equal hashes narrow the search, so this is linear in the number of policies.
std::vector<uint32_t> classesIn(const std::vector<PixelPolicy> &reference, const std::vector<PixelPolicy> &policies) {
    std::vector<std::pair<uint64_t, uint32_t>> byHash;
    byHash.reserve(reference.size());
    for (uint32_t i = 0; i < reference.size(); ++i) byHash.push_back({renderHash(reference[i]), i});
    std::sort(byHash.begin(), byHash.end()); // equal hashes in index order
    std::vector<uint32_t> classes(policies.size(), kNoClass);
    for (size_t p = 0; p < policies.size(); ++p) {
        const uint64_t hash = renderHash(policies[p]);
        for (auto it = std::lower_bound(byHash.begin(), byHash.end(), std::pair<uint64_t, uint32_t>{hash, 0});
             it != byHash.end() && it->first == hash; ++it)
            if (reference[it->second].rendersLike(policies[p])) {
                classes[p] = it->second;
                break;
            }
    }
    return classes;
}

} // namespace

void markChangedPixels(const PolicyMap &before, const PolicyMap &after, const PixelRect &area,
                       std::vector<uint8_t> &changed, int threads) {
    const int width = after.width(), height = after.height();
    if (before.width() != width || before.height() != height)
        throw Error("policy map", "cannot compare a " + std::to_string(before.width()) + "x" +
                                      std::to_string(before.height()) + " map with a " + std::to_string(width) +
                                      "x" + std::to_string(height) + " one");
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (changed.size() < pixels) changed.resize(pixels, 0);
    const int x0 = std::max(area.x0, 0), x1 = std::min(area.x1, width);
    const int y0 = std::max(area.y0, 0), y1 = std::min(area.y1, height);
    if (x0 >= x1 || y0 >= y1) return;

    // Policy indices are mapped once, not per pixel: a policy of either map becomes the
    // smallest index of a `before` policy that renders like it. Equal classes render alike.
    const std::vector<uint32_t> classBefore = classesIn(before.policies(), before.policies());
    const std::vector<uint32_t> classAfter = classesIn(before.policies(), after.policies());

    const auto mixesDiffer = [&](uint32_t mixBefore, uint32_t mixAfter) {
        const std::span<const PolicyTerm> b = before.mixTerms(mixBefore), a = after.mixTerms(mixAfter);
        if (a.size() != b.size()) return true;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (classAfter[a[i].policy] != classBefore[b[i].policy] || a[i].weight != b[i].weight) return true;
        return false;
    };

    const std::size_t rows = std::size_t(y1 - y0);
    parallelForChunks(rows, threads, kRowsPerChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            const int y = y0 + int(r);
            const uint32_t *rowBefore = before.rowMixIndices(y).data();
            const uint32_t *rowAfter = after.rowMixIndices(y).data();
            uint8_t *out = changed.data() + std::size_t(y) * std::size_t(width);
            // Along a row the pair of mixes changes only at lens edges: compare terms there
            // and reuse the answer until the pair changes again.
            uint32_t lastBefore = rowBefore[x0], lastAfter = rowAfter[x0];
            bool differ = mixesDiffer(lastBefore, lastAfter);
            for (int x = x0; x < x1; ++x) {
                if (rowBefore[x] != lastBefore || rowAfter[x] != lastAfter) {
                    lastBefore = rowBefore[x];
                    lastAfter = rowAfter[x];
                    differ = mixesDiffer(lastBefore, lastAfter);
                }
                if (differ) out[x] = 1;
            }
        }
    });
}

} // namespace mvcl
