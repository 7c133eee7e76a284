#include <mvcl/tracer/RayQuery.h>

#include <mvcl/core/Error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace mvcl {

namespace {
bool isFinite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
} // namespace

ClipVolume ClipVolume::orientedBox(const glm::vec3 &center, const glm::vec3 &halfExtent, const glm::mat3 &axes,
                                   Keep keep) {
    const glm::mat3 boxFromScene = glm::transpose(axes);
    const glm::vec3 boxCenter = boxFromScene * center;
    ClipVolume volume = box(boxCenter - halfExtent, boxCenter + halfExtent, keep);
    // Axis-aligned boxes keep the exact fast path (and compare equal to ones made by box()).
    if (axes != glm::mat3(1.f)) {
        volume.m_oriented = true;
        volume.m_boxFromScene = boxFromScene;
    } else {
        volume = box(center - halfExtent, center + halfExtent, keep);
    }
    return volume;
}

bool ClipVolume::isValid() const {
    if (!isFinite(m_point) || !isFinite(m_second) || !std::isfinite(m_scalar)) return false;
    for (int c = 0; c < 3; ++c)
        if (!isFinite(m_boxFromScene[c])) return false;
    switch (m_shape) {
    case Shape::Box: return m_point.x <= m_second.x && m_point.y <= m_second.y && m_point.z <= m_second.z;
    case Shape::Sphere: return m_scalar >= 0.f;
    case Shape::HalfSpace: return m_point != glm::vec3(0.f);
    }
    return false;
}

bool RayQuery::tryAddClip(const ClipVolume &clip) {
    // An identical volume constrains nothing new: keeping it once makes composition idempotent.
    const auto begin = m_clips.begin();
    if (std::find(begin, begin + m_clipCount, clip) != begin + m_clipCount) return true;
    if (m_clipCount >= kMaxClipVolumes) return false;
    m_clips[m_clipCount++] = clip;
    return true;
}

void RayQuery::addClip(const ClipVolume &clip) {
    if (!tryAddClip(clip))
        throw Error("ray query", "holds at most " + std::to_string(kMaxClipVolumes) +
                                     " clip volumes; cannot add another");
}

} // namespace mvcl
