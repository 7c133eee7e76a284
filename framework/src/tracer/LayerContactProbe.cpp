#include <mvcl/tracer/LayerContactProbe.h>

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace mvcl {

namespace {

/// Rounds up to two significant digits, so the suggestion reads like a value a person would type.
double roundUpTwoDigits(double x) {
    if (!(x > 0.0)) return 0.0;
    const double scale = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return std::ceil(x / scale) * scale;
}

} // namespace

LayerContactReport probeLayerContacts(const Tracer &tracer, const LayerContactProbeSettings &settings) {
    const Scene &scene = tracer.scene();
    LayerContactReport report;
    const Bounds3f bounds = scene.bounds();
    if (bounds.isEmpty()) return report;
    const double size = double(glm::length(bounds.extent()));
    if (!(size > 0.0)) return report;
    const float reach = float(settings.reach * size);

    struct PairStats {
        std::size_t samples = 0, sampled = 0;
        double maxSeparation = 0.0;
    };
    std::map<std::pair<int, int>, PairStats> pairs;
    for (const TriangleMesh &mesh : scene.meshes) {
        const std::size_t count = mesh.indices.size();
        if (count == 0) continue;
        const std::size_t samples = std::min(count, settings.samplesPerMesh);
        RayQuery query;
        query.layerMask = ~layerBit(mesh.layer);
        // Per other layer: how many of this mesh's samples found it, and the farthest of those.
        std::map<int, PairStats> found;
        std::size_t probed = 0;
        for (std::size_t k = 0; k < samples; ++k) {
            const glm::uvec3 tri = mesh.indices[k * count / samples];
            const std::size_t nv = mesh.positions.size();
            if (tri.x >= nv || tri.y >= nv || tri.z >= nv) continue;
            const glm::dvec3 p0(mesh.positions[tri.x]), p1(mesh.positions[tri.y]), p2(mesh.positions[tri.z]);
            const glm::dvec3 cross = glm::cross(p1 - p0, p2 - p0);
            const double area = glm::length(cross);
            if (!(area > 0.0) || !std::isfinite(area)) continue;
            ++probed;
            const glm::dvec3 centroid = (p0 + p1 + p2) / 3.0;
            const glm::dvec3 n = cross / area;
            // One ray through the centroid along the normal, from `reach` behind it to `reach`
            // beyond, stepping from hit to hit: the hits nearest the centroid on either side,
            // a coincident surface (at the centroid itself) included.
            const Ray ray{glm::vec3(centroid - double(reach) * n), glm::vec3(n)};
            RayQuery step = query;
            step.tMax = 2.f * reach;
            double nearest = -1.0;
            int nearestLayer = -1;
            Hit hit;
            for (int k = 0; k < 16 && tracer.closestHit(ray, step, hit); ++k) {
                const double separation = std::fabs(double(hit.t) - double(reach));
                if (nearestLayer < 0 || separation < nearest) {
                    nearest = separation;
                    nearestLayer = hit.layer;
                }
                if (hit.t >= reach) break; // the first hit beyond the centroid ends the walk
                step.tMin = std::nextafter(hit.t, 2.f * reach);
            }
            if (nearestLayer < 0) continue;
            PairStats &s = found[nearestLayer];
            ++s.samples;
            s.maxSeparation = std::max(s.maxSeparation, nearest);
        }
        for (const auto &[other, s] : found) {
            if (double(s.samples) < settings.minimumFraction * double(probed)) continue;
            PairStats &p = pairs[{std::min(mesh.layer, other), std::max(mesh.layer, other)}];
            p.samples += s.samples;
            p.sampled += probed;
            p.maxSeparation = std::max(p.maxSeparation, s.maxSeparation);
        }
    }
    double largest = 0.0;
    for (const auto &[layers, s] : pairs) {
        if (layers.first == layers.second) continue;
        report.pairs.push_back({layers.first, layers.second, s.samples, s.sampled, s.maxSeparation});
        largest = std::max(largest, s.maxSeparation);
    }
    // Separations of a few float steps are what the tracer's priority within the error bound
    // already absorbs: no tolerance for those.
    const double relative = 1.5 * largest / size;
    if (relative >= LayerContactReport::kNoToleranceBelow) report.suggested.distance = roundUpTwoDigits(relative);
    return report;
}

} // namespace mvcl
