#include <mvcl/tracer/LayerInference.h>

#include <mvcl/core/Error.h>
#include <mvcl/core/FloatBits.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace mvcl {

// Onion peeling by ray casting (see LayerInference.h and docs/gltf-loading.md).
//
// One Tracer is built over the whole scene once. "Removing" a peeled mesh does not rebuild it:
// a ray that hits the sample's own mesh, an already peeled mesh, a sphere or a plane simply
// continues from just past that hit (a bounded loop). A sample is enclosed when, in all six axis
// directions, the first hit on an *active* other mesh exists.

namespace {

/// Hits skipped along one ray before we give up and call the direction open. Rays through
/// removed layers cross a few surfaces each; 64 is far more than real models need.
constexpr int kMaxSkippedHits = 64;

/// A part is what gets peeled: all TriangleMeshes of one glTF node (the loader splits a node by
/// material, but a spring with two materials is still one spring), or a single mesh otherwise.
struct Part {
    std::vector<uint32_t> meshes;
    bool unassigned = false;
    std::vector<glm::vec3> samples;
};

struct PeelState {
    const Tracer *tracer = nullptr;
    const std::vector<uint32_t> *partOf = nullptr; // mesh → part
    const std::vector<char> *active = nullptr;     // per mesh: still part of the onion
};

bool directionBlocked(const PeelState &state, const glm::vec3 &origin, const glm::vec3 &dir, uint32_t self) {
    Ray ray{origin, dir};
    RayQuery query;
    query.tMin = 0.f;
    for (int i = 0; i < kMaxSkippedHits; ++i) {
        Hit hit;
        if (!state.tracer->closestHit(ray, query, hit)) return false;
        if (hit.kind == GeometryKind::Triangle && hit.geometry < state.active->size() &&
            (*state.active)[hit.geometry] && (*state.partOf)[hit.geometry] != self)
            return true;
        query.tMin = nextFloatUp(hit.t);
        if (!(query.tMin < query.tMax)) return false;
    }
    return false;
}

/// The six axis directions, then Fibonacci points on the sphere up to `count` (deterministic).
std::vector<glm::vec3> sampleDirections(int count) {
    std::vector<glm::vec3> dirs = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const int extra = std::max(count, 6) - 6;
    const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < extra; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / double(extra);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = golden * i;
        dirs.emplace_back(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
    }
    return dirs;
}

bool isEnclosed(const PeelState &state, const std::vector<glm::vec3> &dirs, float hiddenFraction,
                const glm::vec3 &p, uint32_t self) {
    // Stop as soon as the answer is known: too many open rays, or enough blocked ones.
    const int needed = int(std::ceil(hiddenFraction * float(dirs.size()) - 1e-4f));
    int blocked = 0, open = 0;
    const int allowedOpen = int(dirs.size()) - needed;
    for (const glm::vec3 &d : dirs) {
        if (directionBlocked(state, p, d, self)) {
            if (++blocked >= needed) return true;
        } else if (++open > allowedOpen) {
            return false;
        }
    }
    return blocked >= needed;
}

/// Centroids of up to `count` triangles at evenly spaced indices over the part's triangles
/// (deterministic, and spread over the whole part because exporters emit triangles in
/// spatially coherent order).
std::vector<glm::vec3> samplePoints(const Scene &scene, const std::vector<uint32_t> &meshes, int count) {
    std::vector<glm::vec3> points;
    std::uint64_t triangles = 0;
    for (uint32_t m : meshes) triangles += scene.meshes[m].indices.size();
    if (triangles == 0 || count <= 0) return points;
    const std::uint64_t n = std::min<std::uint64_t>(triangles, std::uint64_t(count));
    points.reserve(std::size_t(n));
    std::size_t mesh = 0;
    std::uint64_t before = 0; // triangles in meshes[0 .. mesh)
    for (std::uint64_t k = 0; k < n; ++k) {
        const std::uint64_t t = ((2 * k + 1) * triangles) / (2 * n);
        while (t >= before + scene.meshes[meshes[mesh]].indices.size()) before += scene.meshes[meshes[mesh++]].indices.size();
        const TriangleMesh &m = scene.meshes[meshes[mesh]];
        const glm::uvec3 &tri = m.indices[std::size_t(t - before)];
        if (tri.x >= m.positions.size() || tri.y >= m.positions.size() || tri.z >= m.positions.size()) continue;
        points.push_back((m.positions[tri.x] + m.positions[tri.y] + m.positions[tri.z]) / 3.f);
    }
    return points;
}

} // namespace

namespace {

/// Either public form: `given` is the caller's tracer, or null to build one when peeling needs it.
LayerInferenceResult infer(Scene &scene, const Tracer *given, const LayerInferenceSettings &settings) {
    LayerInferenceResult result;
    const std::size_t meshCount = scene.meshes.size();
    bool anyUnassigned = false;
    for (const TriangleMesh &m : scene.meshes) anyUnassigned |= m.layerSource == LayerSource::Unassigned;
    if (!anyUnassigned) return result;

    // Group meshes into parts by (glTF node, unassigned or not).
    std::vector<Part> parts;
    std::vector<uint32_t> partOf(meshCount);
    std::map<std::pair<int, bool>, uint32_t> byNode;
    for (std::size_t i = 0; i < meshCount; ++i) {
        const TriangleMesh &m = scene.meshes[i];
        const bool unassigned = m.layerSource == LayerSource::Unassigned;
        uint32_t part = uint32_t(parts.size());
        if (m.sourceNode >= 0) {
            const auto [it, inserted] = byNode.try_emplace({m.sourceNode, unassigned}, part);
            part = it->second;
        }
        if (part == parts.size()) parts.push_back(Part{{}, unassigned, {}});
        parts[part].meshes.push_back(uint32_t(i));
        partOf[i] = part;
    }
    std::vector<uint32_t> remaining; // unassigned parts not yet peeled
    for (std::size_t p = 0; p < parts.size(); ++p) {
        if (!parts[p].unassigned) continue;
        parts[p].samples = samplePoints(scene, parts[p].meshes, std::max(settings.samplesPerMesh, 1));
        remaining.push_back(uint32_t(p));
    }

    const int firstLayer = std::clamp(settings.firstLayer, 0, kMaxLayers - 1);
    std::vector<int> assigned(parts.size(), -1);
    std::vector<float> confidence(parts.size(), 0.f);
    if (parts.size() == 1) {
        // One part and no other triangle to enclose it (spheres and planes never do): the first
        // peel takes it, wholly seen from outside. A one-mesh file (an STL, a scan) so skips a
        // BVH built only to find that out.
        assigned[0] = firstLayer;
        confidence[0] = firstLayer == kMaxLayers - 1 ? 0.f : 1.f;
    } else {
        // The tracer reads the scene; layers are written back only after its last query.
        std::optional<Tracer> own;
        if (!given) own.emplace(scene);
        const Tracer &tracer = given ? *given : *own;
        std::vector<char> active(meshCount, 0);
        std::vector<float> fraction(parts.size(), 0.f);
        PeelState state{&tracer, &partOf, &active};
        const std::vector<glm::vec3> directions = sampleDirections(settings.directions);

        int layer = firstLayer;
        while (!remaining.empty()) {
            if (layer == kMaxLayers - 1) { // out of layers: everything left is innermost
                for (uint32_t p : remaining) {
                    assigned[p] = layer;
                    confidence[p] = 0.f;
                }
                break;
            }
            // Active = not yet peeled, or preset meshes of this layer or deeper.
            for (std::size_t i = 0; i < meshCount; ++i) {
                const TriangleMesh &mesh = scene.meshes[i];
                active[i] = mesh.layerSource == LayerSource::Unassigned ? char(assigned[partOf[i]] < 0)
                                                                         : char(mesh.layer >= layer);
            }
            // One part per item, on all cores: each writes only its own fraction.
            parallelFor(remaining.size(), 0, [&](std::size_t k) {
                const uint32_t p = remaining[k];
                const auto &points = parts[p].samples;
                std::size_t enclosed = 0;
                for (const glm::vec3 &pt : points)
                    enclosed += isEnclosed(state, directions, settings.hiddenFraction, pt, p) ? 1 : 0;
                fraction[p] = points.empty() ? 0.f : float(enclosed) / float(points.size());
            });

            std::vector<uint32_t> peel;
            for (uint32_t p : remaining)
                if (fraction[p] < settings.enclosedFraction) peel.push_back(p);
            if (peel.empty()) {
                const bool presetHere = std::any_of(scene.meshes.begin(), scene.meshes.end(), [&](const TriangleMesh &m) {
                    return m.layerSource != LayerSource::Unassigned && m.layer == layer;
                });
                if (presetHere) { // the preset meshes of this layer are the peel
                    ++layer;
                    continue;
                }
                // Mutual enclosure (e.g. coincident shells): peel the least enclosed.
                float least = 2.f;
                for (uint32_t p : remaining) least = std::min(least, fraction[p]);
                for (uint32_t p : remaining)
                    if (fraction[p] == least) peel.push_back(p);
            }
            const float threshold = std::max(settings.enclosedFraction, 1e-6f);
            for (uint32_t p : peel) {
                assigned[p] = layer;
                confidence[p] = std::clamp((threshold - fraction[p]) / threshold, 0.f, 1.f);
            }
            std::erase_if(remaining, [&](uint32_t p) { return assigned[p] >= 0; });
            ++layer;
        }
    }

    std::set<int> layers;
    for (std::size_t i = 0; i < meshCount; ++i) {
        const int layer = assigned[partOf[i]];
        if (layer < 0) continue;
        TriangleMesh &mesh = scene.meshes[i];
        mesh.layer = layer;
        mesh.layerSource = LayerSource::Inferred;
        mesh.layerConfidence = confidence[partOf[i]];
        scene.layers.ensure(layer);
        layers.insert(layer);
        ++result.meshesAssigned;
    }
    result.layerCount = int(layers.size());
    return result;
}

} // namespace

LayerInferenceResult inferLayersByContainment(Scene &scene, const LayerInferenceSettings &settings) {
    return infer(scene, nullptr, settings);
}

LayerInferenceResult inferLayersByContainment(Scene &scene, const Tracer &tracer,
                                              const LayerInferenceSettings &settings) {
    if (tracer.scene().meshes.size() != scene.meshes.size())
        throw Error("layer inference", "the tracer was built over another scene (" +
                                           std::to_string(tracer.scene().meshes.size()) + " meshes, not " +
                                           std::to_string(scene.meshes.size()) + ")");
    return infer(scene, &tracer, settings);
}

} // namespace mvcl
