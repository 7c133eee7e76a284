#include <mvcl/lens/PolicyComposition.h>

#include <mvcl/core/Error.h>

#include <algorithm>

namespace mvcl {

RayQuery intersectQueries(const RayQuery &a, const RayQuery &b) {
    RayQuery q = a;
    q.layerMask = a.layerMask & b.layerMask;
    q.tMin = std::max(a.tMin, b.tMin);
    q.tMax = std::min(a.tMax, b.tMax);
    for (int i = 0; i < b.clipCount; ++i) {
        const ClipVolume &clip = b.clips[size_t(i)];
        // An identical volume constrains nothing new: keeping it once makes the rule idempotent.
        const auto begin = q.clips.begin();
        if (std::any_of(begin, begin + q.clipCount, [&](const ClipVolume &c) { return c == clip; }))
            continue;
        if (q.clipCount >= kMaxClipVolumes)
            throw Error("lens stack", "overlapping lenses use more than " + std::to_string(kMaxClipVolumes) +
                                          " clip volumes on one ray type");
        q.clips[q.clipCount++] = clip;
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

PixelPolicy applyContribution(const PixelPolicy &below, const LensContribution &lens) {
    PixelPolicy p = below;
    for (int t = 0; t < kRayTypeCount; ++t)
        p.ray.visibility[size_t(t)] = intersectQueries(below.ray.visibility[size_t(t)], lens.visibility[size_t(t)]);
    lens.shading.applyTo(p.ray.shading);
    if (!lens.color.isIdentity()) p.ray.color = composeColor(below.ray.color, lens.color);
    // The upper lens looks at the image the lower ones make: its map is applied to the pixel
    // position first, then the lower lenses' maps.
    p.sampleFromScreen = below.sampleFromScreen * lens.sampleFromScreen;
    return p;
}

} // namespace mvcl
