#include <mvcl/lens/PolicyComposition.h>

#include <glm/common.hpp>

#include <algorithm>

namespace mvcl {

namespace {
// Folds `clip` into a volume of `query` whose intersection with it has the same shape: two
// kept-inside boxes with the same axes (their overlap is a box), or two half-spaces of the same
// normal and keep — each pair acting on the same layers and drawing the same caps. True if it
// did, so the query needs no new slot.
bool mergeInto(RayQuery &query, const ClipVolume &clip) {
    using Shape = ClipVolume::Shape;
    using Keep = ClipVolume::Keep;
    RayQuery merged;
    bool done = false;
    for (const ClipVolume &c : query.clips()) {
        ClipVolume next = c;
        if (!done && c.keep() == clip.keep() && c.shape() == clip.shape() && c.layerMask() == clip.layerMask() &&
            c.capStyle() == clip.capStyle()) {
            if (c.shape() == Shape::Box && c.keep() == Keep::Inside && c.boxFromScene() == clip.boxFromScene()) {
                next = c.withBox(glm::max(c.boxMin(), clip.boxMin()), glm::min(c.boxMax(), clip.boxMax()));
                done = true;
            } else if (c.shape() == Shape::HalfSpace && c.normal() == clip.normal()) {
                // Kept inside: both hold, the larger offset. Cut away: either cuts, the smaller.
                const float offset = c.keep() == Keep::Inside ? std::max(c.offset(), clip.offset())
                                                              : std::min(c.offset(), clip.offset());
                next = c.withOffset(offset);
                done = true;
            }
        }
        merged.tryAddClip(next);
    }
    if (done) {
        query.clearClips();
        for (const ClipVolume &c : merged.clips()) query.tryAddClip(c);
    }
    return done;
}
} // namespace

RayQuery intersectQueries(const RayQuery &a, const RayQuery &b, int *droppedClips) {
    RayQuery q = a;
    q.layerMask = a.layerMask & b.layerMask;
    q.tMin = std::max(a.tMin, b.tMin);
    q.tMax = std::min(a.tMax, b.tMax);
    for (const ClipVolume &clip : b.clips()) {
        if (q.tryAddClip(clip) || mergeInto(q, clip)) continue;
        if (droppedClips) ++*droppedClips;
    }
    return q;
}

ColorPolicy composeColor(const ColorPolicy &lower, const ColorPolicy &upper) {
    // upper(lower(c)) = U·(L·c + l) + u
    ColorPolicy c;
    c.matrix = upper.matrix * lower.matrix;
    c.offset = upper.matrix * lower.offset + upper.offset;
    return c;
}

PixelPolicy applyContribution(const PixelPolicy &below, const LensContribution &lens, int *droppedClips) {
    PixelPolicy p = below;
    for (int t = 0; t < kRayTypeCount; ++t)
        p.ray.visibility[size_t(t)] =
            intersectQueries(below.ray.visibility[size_t(t)], lens.visibility[size_t(t)], droppedClips);
    lens.shading.applyTo(p.ray.shading);
    if (!lens.color.isIdentity()) p.ray.color = composeColor(below.ray.color, lens.color);
    // The upper lens looks at the image the lower ones make: its map is applied to the pixel
    // position first, then the lower lenses' maps.
    p.sampleFromScreen = below.sampleFromScreen * lens.sampleFromScreen;
    return p;
}

} // namespace mvcl
