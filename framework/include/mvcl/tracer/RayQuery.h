#pragma once
/// \file RayQuery.h
/// What a single trace may hit: a t-range, a layer mask and clip volumes. Plain data: the tracer
/// applies it inside traversal without any virtual call.

#include <mvcl/model/LayerTable.h>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <limits>

namespace mvcl {

/// A region of space whose hits are discarded (a cut) or kept exclusively.
struct ClipVolume {
    enum class Shape : uint8_t {
        Box,       ///< axis-aligned box [a, b]
        Sphere,    ///< centre a, radius `radius`
        HalfSpace, ///< {p : dot(a, p) ≥ radius}; a is the unit normal
    };
    enum class Keep : uint8_t {
        Outside, ///< hits inside the volume are removed (a cutaway)
        Inside,  ///< only hits inside the volume survive
    };
    Shape shape = Shape::Box;
    Keep keep = Keep::Outside;
    glm::vec3 a{0.f};
    glm::vec3 b{0.f};
    float radius = 0.f;

    bool contains(const glm::vec3 &p) const {
        switch (shape) {
        case Shape::Box:
            return p.x >= a.x && p.y >= a.y && p.z >= a.z && p.x <= b.x && p.y <= b.y && p.z <= b.z;
        case Shape::Sphere: {
            const glm::vec3 d = p - a;
            return d.x * d.x + d.y * d.y + d.z * d.z <= radius * radius;
        }
        case Shape::HalfSpace:
            return a.x * p.x + a.y * p.y + a.z * p.z >= radius;
        }
        return false;
    }
    /// True if a hit at p survives this volume.
    bool accepts(const glm::vec3 &p) const { return contains(p) == (keep == Keep::Inside); }

    bool operator==(const ClipVolume &other) const = default;
};

inline constexpr int kMaxClipVolumes = 8;

struct RayQuery {
    /// Hits with t < tMin or t > tMax are ignored (t in units of the ray direction's length).
    float tMin = 0.f;
    float tMax = std::numeric_limits<float>::infinity();
    /// Bit i set: layer i may be hit.
    uint32_t layerMask = kAllLayers;
    /// Hits must be accepted by every clip volume (intersection of constraints).
    std::array<ClipVolume, kMaxClipVolumes> clips{};
    uint8_t clipCount = 0;

    bool acceptsPoint(const glm::vec3 &p) const {
        for (int i = 0; i < clipCount; ++i)
            if (!clips[i].accepts(p)) return false;
        return true;
    }

    /// Same range, mask and clip volumes in the same order. Slots past clipCount are not
    /// compared: the tracer never reads them, so they cannot make two queries trace apart.
    bool operator==(const RayQuery &other) const {
        if (tMin != other.tMin || tMax != other.tMax || layerMask != other.layerMask || clipCount != other.clipCount)
            return false;
        for (int i = 0; i < clipCount; ++i)
            if (!(clips[size_t(i)] == other.clips[size_t(i)])) return false;
        return true;
    }
};

} // namespace mvcl
