#pragma once
/// \file RayQuery.h
/// What a single trace may hit: a t-range, a layer mask and clip volumes. Plain data: the tracer
/// applies it inside traversal without any virtual call.

#include <mvcl/core/Export.h>

#include <mvcl/model/LayerTable.h>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <span>

namespace mvcl {

/// A region of scene space whose hits are discarded (a cut) or kept exclusively. Made by one of
/// the factories; the accessors name what each shape stores. A volume acts on the layers of
/// its layer mask only (all by default): hits on other layers pass it untouched, and it caps
/// only the solids it cuts.
class MVCL_EXPORT ClipVolume {
public:
    enum class Shape : uint8_t {
        Box,       ///< box [boxMin, boxMax] in its own axes (boxAxes(); the scene's axes unless oriented)
        Sphere,    ///< ball of `radius` around `center`
        HalfSpace, ///< {p : dot(normal, p) ≥ offset}
    };
    enum class Keep : uint8_t {
        Outside, ///< hits inside the volume are removed (a cutaway)
        Inside,  ///< only hits inside the volume survive
    };
    /// What a primary ray shows where the volume's surface cuts through a closed mesh
    /// (MeshClosure): the hollow inside, or a cap in the colour of the mesh it cuts.
    enum class CapStyle : uint8_t {
        None,    ///< the inside of the shell shows
        Solid,   ///< a lit cap on the cut surface
        Hatched, ///< a lit cap with dark diagonal stripes, as in engineering drawings
    };

    ClipVolume() = default; ///< the empty box at the origin, cut away (removes nothing)
    static ClipVolume box(const glm::vec3 &boxMin, const glm::vec3 &boxMax, Keep keep) {
        return {Shape::Box, keep, boxMin, boxMax, 0.f};
    }
    /// A box turned about its centre: `axes` (columns, orthonormal) are its sides' directions
    /// in scene space, `halfExtent` half its side lengths along them.
    static ClipVolume orientedBox(const glm::vec3 &center, const glm::vec3 &halfExtent, const glm::mat3 &axes,
                                  Keep keep);
    static ClipVolume sphere(const glm::vec3 &center, float radius, Keep keep) {
        return {Shape::Sphere, keep, center, glm::vec3(0.f), radius};
    }
    /// `normal` need not be unit length; the test is dot(normal, p) ≥ offset either way.
    static ClipVolume halfSpace(const glm::vec3 &normal, float offset, Keep keep) {
        return {Shape::HalfSpace, keep, normal, glm::vec3(0.f), offset};
    }

    Shape shape() const { return m_shape; }
    Keep keep() const { return m_keep; }
    CapStyle capStyle() const { return m_capStyle; }
    void setCapStyle(CapStyle style) { m_capStyle = style; }
    /// Bit i set: hits on layer i are subject to the volume (kAllLayers by default).
    uint32_t layerMask() const { return m_layers; }
    void setLayerMask(uint32_t mask) { m_layers = mask; }
    bool appliesTo(uint32_t layer) const { return (m_layers >> layer) & 1u; }
    /// Box: corners in the box's own axes (boxFromScene() * p for a scene point p).
    const glm::vec3 &boxMin() const { return m_point; }   ///< Box
    const glm::vec3 &boxMax() const { return m_second; }  ///< Box
    bool isOriented() const { return m_oriented; }        ///< Box turned off the scene axes
    /// Box: its axes in scene space (columns); the identity unless oriented.
    glm::mat3 boxAxes() const { return glm::transpose(m_boxFromScene); }
    const glm::mat3 &boxFromScene() const { return m_boxFromScene; }
    const glm::vec3 &center() const { return m_point; }   ///< Sphere
    float radius() const { return m_scalar; }             ///< Sphere
    const glm::vec3 &normal() const { return m_point; }   ///< HalfSpace
    float offset() const { return m_scalar; }             ///< HalfSpace

    /// The same volume (axes, layers, caps) with other corners (Box) or another offset (HalfSpace).
    ClipVolume withBox(const glm::vec3 &boxMin, const glm::vec3 &boxMax) const {
        ClipVolume v = *this;
        v.m_point = boxMin, v.m_second = boxMax;
        return v;
    }
    ClipVolume withOffset(float offset) const {
        ClipVolume v = *this;
        v.m_scalar = offset;
        return v;
    }

    /// Every number finite, a box's min ≤ max per axis, a radius ≥ 0, a half-space's normal
    /// not zero: what Lens::commit() checks of every clip volume a lens contributes.
    bool isValid() const;

    bool contains(const glm::vec3 &scenePoint) const {
        switch (m_shape) {
        case Shape::Box: {
            const glm::vec3 p = m_oriented ? m_boxFromScene * scenePoint : scenePoint;
            return p.x >= m_point.x && p.y >= m_point.y && p.z >= m_point.z && p.x <= m_second.x &&
                   p.y <= m_second.y && p.z <= m_second.z;
        }
        case Shape::Sphere: {
            const glm::vec3 d = scenePoint - m_point;
            return d.x * d.x + d.y * d.y + d.z * d.z <= m_scalar * m_scalar;
        }
        case Shape::HalfSpace:
            return m_point.x * scenePoint.x + m_point.y * scenePoint.y + m_point.z * scenePoint.z >= m_scalar;
        }
        return false;
    }
    /// True if a hit at p on `layer` survives this volume.
    bool accepts(const glm::vec3 &p, uint32_t layer) const {
        return !appliesTo(layer) || contains(p) == (m_keep == Keep::Inside);
    }

    bool operator==(const ClipVolume &other) const = default;

private:
    ClipVolume(Shape shape, Keep keep, const glm::vec3 &point, const glm::vec3 &second, float scalar)
        : m_shape(shape), m_keep(keep), m_point(point), m_second(second), m_scalar(scalar) {}

    Shape m_shape = Shape::Box;
    Keep m_keep = Keep::Outside;
    CapStyle m_capStyle = CapStyle::None;
    bool m_oriented = false;
    uint32_t m_layers = kAllLayers;
    glm::mat3 m_boxFromScene{1.f}; // box: rows are its axes
    glm::vec3 m_point{0.f};  // box min, sphere centre, half-space normal
    glm::vec3 m_second{0.f}; // box max
    float m_scalar = 0.f;    // sphere radius, half-space offset
};

inline constexpr int kMaxClipVolumes = 8;

struct MVCL_EXPORT RayQuery {
    /// Hits with t < tMin or t > tMax are ignored (t in units of the ray direction's length).
    float tMin = 0.f;
    float tMax = std::numeric_limits<float>::infinity();
    /// Bit i set: layer i may be hit.
    uint32_t layerMask = kAllLayers;

    /// Adds a clip volume: hits must be accepted by every one (intersection of constraints).
    /// A volume equal to one already there is not added again. Throws mvcl::Error("ray query",
    /// ...) when the query already holds kMaxClipVolumes others (inside contribute() that is
    /// reported by Lens::commit(), never on the render path).
    void addClip(const ClipVolume &clip);
    /// Adds `clip` if there is room or it is already there; false (and the query unchanged) if
    /// the query is full. For composition code that must not throw.
    bool tryAddClip(const ClipVolume &clip);
    void clearClips() { m_clipCount = 0; }
    int clipCount() const { return m_clipCount; }
    const ClipVolume &clip(int index) const { return m_clips[size_t(index)]; }
    std::span<const ClipVolume> clips() const { return {m_clips.data(), size_t(m_clipCount)}; }

    /// A hit at p on `layer` survives every clip volume.
    bool acceptsPoint(const glm::vec3 &p, uint32_t layer) const {
        for (int i = 0; i < m_clipCount; ++i)
            if (!m_clips[size_t(i)].accepts(p, layer)) return false;
        return true;
    }

    /// Same range, mask and clip volumes in the same order. Slots past clipCount() are not
    /// compared: the tracer never reads them, so they cannot make two queries trace apart.
    bool operator==(const RayQuery &other) const {
        if (tMin != other.tMin || tMax != other.tMax || layerMask != other.layerMask ||
            m_clipCount != other.m_clipCount)
            return false;
        for (int i = 0; i < m_clipCount; ++i)
            if (!(m_clips[size_t(i)] == other.m_clips[size_t(i)])) return false;
        return true;
    }

private:
    std::array<ClipVolume, kMaxClipVolumes> m_clips{};
    uint8_t m_clipCount = 0;
};

} // namespace mvcl
