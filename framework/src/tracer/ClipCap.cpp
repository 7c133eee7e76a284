#include "ClipCap.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

namespace mvcl::detail {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Where the ray is inside a volume: [enter, leave] with the outward normals there. Empty when
/// enter > leave; a half-space may have an infinite end.
struct Span {
    double enter = kInfinity, leave = -kInfinity;
    glm::dvec3 enterNormal{0.0}, leaveNormal{0.0};
};

Span spanOf(const ClipVolume &volume, const glm::dvec3 &o, const glm::dvec3 &d) {
    Span span;
    switch (volume.shape()) {
    case ClipVolume::Shape::Box: {
        if (volume.isOriented()) {
            // The same slabs in the box's own axes; its normals turned back into scene space.
            const glm::dmat3 boxFromScene(volume.boxFromScene());
            ClipVolume aligned = ClipVolume::box(volume.boxMin(), volume.boxMax(), volume.keep());
            Span local = spanOf(aligned, boxFromScene * o, boxFromScene * d);
            const glm::dmat3 sceneFromBox = glm::transpose(boxFromScene);
            local.enterNormal = sceneFromBox * local.enterNormal;
            local.leaveNormal = sceneFromBox * local.leaveNormal;
            return local;
        }
        const glm::dvec3 lo(volume.boxMin()), hi(volume.boxMax());
        span.enter = -kInfinity;
        span.leave = kInfinity;
        for (int axis = 0; axis < 3; ++axis) {
            if (d[axis] == 0.0) {
                if (o[axis] < lo[axis] || o[axis] > hi[axis]) return {};
                continue;
            }
            double near = (lo[axis] - o[axis]) / d[axis], far = (hi[axis] - o[axis]) / d[axis];
            glm::dvec3 nearNormal(0.0);
            nearNormal[axis] = -1.0;
            if (near > far) {
                std::swap(near, far);
                nearNormal[axis] = 1.0;
            }
            if (near > span.enter) span.enter = near, span.enterNormal = nearNormal;
            if (far < span.leave) span.leave = far, span.leaveNormal = -nearNormal;
        }
        return span;
    }
    case ClipVolume::Shape::Sphere: {
        const glm::dvec3 c(volume.center());
        const double r = volume.radius();
        const glm::dvec3 oc = o - c;
        const double a = glm::dot(d, d), b = glm::dot(oc, d), cc = glm::dot(oc, oc) - r * r;
        const double discriminant = b * b - a * cc;
        if (!(a > 0.0) || discriminant < 0.0) return {};
        const double root = std::sqrt(discriminant);
        span.enter = (-b - root) / a;
        span.leave = (-b + root) / a;
        span.enterNormal = r > 0.0 ? (oc + span.enter * d) / r : -d;
        span.leaveNormal = r > 0.0 ? (oc + span.leave * d) / r : d;
        return span;
    }
    case ClipVolume::Shape::HalfSpace: {
        const glm::dvec3 n(volume.normal());
        const double along = glm::dot(n, d), side = glm::dot(n, o) - double(volume.offset());
        // Inside is n·p ≥ offset; the outward normal is −n.
        const glm::dvec3 outward = -glm::normalize(n);
        if (along == 0.0) return side >= 0.0 ? Span{-kInfinity, kInfinity, outward, outward} : Span{};
        const double crossing = -side / along;
        if (along > 0.0) return {crossing, kInfinity, outward, outward};
        return {-kInfinity, crossing, outward, outward};
    }
    }
    return {};
}

} // namespace

bool hasCappedClip(const RayQuery &query) {
    for (const ClipVolume &clip : query.clips())
        if (clip.capStyle() != ClipVolume::CapStyle::None) return true;
    return false;
}

std::optional<ClipCap> clipCapBefore(const Ray &ray, const RayQuery &query, float hitT, uint32_t layer) {
    const glm::dvec3 o(ray.origin), d(ray.direction);
    const double h = hitT;
    // The run that holds h is the intersection of each volume's accepted run holding h, so it
    // begins at the latest of their beginnings.
    double runStart = -kInfinity;
    glm::dvec3 startNormal(0.0);
    ClipVolume::CapStyle startStyle = ClipVolume::CapStyle::None;
    uint32_t startLayers = 0;
    for (const ClipVolume &clip : query.clips()) {
        if (!clip.appliesTo(layer)) continue; // it neither cuts nor caps this layer
        const Span span = spanOf(clip, o, d);
        double start = -kInfinity;
        glm::dvec3 normal(0.0);
        if (clip.keep() == ClipVolume::Keep::Inside) {
            // Accepted inside: the run begins where the ray enters.
            if (!(span.enter <= h && h <= span.leave)) return std::nullopt; // rounding: no cap
            start = span.enter, normal = span.enterNormal;
        } else if (span.enter <= span.leave && h > span.leave) {
            // Accepted outside, hit beyond the volume: the run begins where the ray leaves it.
            start = span.leave, normal = span.leaveNormal;
        }
        if (start > runStart)
            runStart = start, startNormal = normal, startStyle = clip.capStyle(), startLayers = clip.layerMask();
    }
    if (startStyle == ClipVolume::CapStyle::None || !(runStart > double(query.tMin)) || !(runStart < h) ||
        !std::isfinite(runStart))
        return std::nullopt;
    if (glm::dot(startNormal, d) > 0.0) startNormal = -startNormal;
    const double length = glm::length(startNormal);
    if (!(length > 0.0)) return std::nullopt;
    return ClipCap{float(runStart), glm::vec3(startNormal / length), startStyle, startLayers};
}

std::optional<ClipCap> nearestClipCap(const Ray &ray, const RayQuery &query, float hitT, uint32_t hitLayer) {
    std::optional<ClipCap> nearest = clipCapBefore(ray, query, hitT, hitLayer);
    // Volumes that act on the hit's layer were counted; those that spare it cut other layers,
    // whose runs (one layer of each mask stands for it) may begin on a cap in front of the hit.
    uint32_t triedMasks[kMaxClipVolumes];
    int tried = 0;
    for (const ClipVolume &clip : query.clips()) {
        const uint32_t mask = clip.layerMask();
        if (clip.capStyle() == ClipVolume::CapStyle::None || mask == 0 || clip.appliesTo(hitLayer) ||
            std::find(triedMasks, triedMasks + tried, mask) != triedMasks + tried)
            continue;
        triedMasks[tried++] = mask;
        const std::optional<ClipCap> cap = clipCapBefore(ray, query, hitT, uint32_t(std::countr_zero(mask)));
        if (cap && (!nearest || cap->t < nearest->t)) nearest = cap;
    }
    return nearest;
}

std::optional<ClipCap> firstCappedRunStart(const Ray &ray, const RayQuery &query) {
    const glm::dvec3 o(ray.origin), d(ray.direction);
    // Runs are per layer once volumes spare layers; those of the first capped volume's lowest
    // layer stand for all (one lens's volumes share their layers).
    uint32_t layer = kMaxLayers;
    for (const ClipVolume &clip : query.clips())
        if (clip.capStyle() != ClipVolume::CapStyle::None && clip.layerMask() != 0) {
            layer = uint32_t(std::countr_zero(clip.layerMask()));
            break;
        }
    if (layer == kMaxLayers) return std::nullopt;
    std::vector<double> boundaries;
    for (const ClipVolume &clip : query.clips()) {
        if (!clip.appliesTo(layer)) continue;
        const Span span = spanOf(clip, o, d);
        if (span.enter > span.leave) continue;
        for (const double t : {span.enter, span.leave})
            if (std::isfinite(t) && t > double(query.tMin) && t < double(query.tMax)) boundaries.push_back(t);
    }
    std::sort(boundaries.begin(), boundaries.end());
    // A run begins at a boundary whose following stretch is accepted; the middle of the
    // stretch stands for all of it.
    for (size_t i = 0; i < boundaries.size(); ++i) {
        const double next = i + 1 < boundaries.size() ? boundaries[i + 1] : boundaries[i] + 1.0 + std::abs(boundaries[i]);
        const double middle = 0.5 * (boundaries[i] + next);
        if (!(next > boundaries[i]) || !query.acceptsPoint(glm::vec3(o + middle * d), layer)) continue;
        return clipCapBefore(ray, query, float(middle), layer);
    }
    return std::nullopt;
}

} // namespace mvcl::detail
