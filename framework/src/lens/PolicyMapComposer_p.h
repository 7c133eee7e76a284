#pragma once
/// \file PolicyMapComposer_p.h
/// Private to LensStack: composing a frame's lens snapshots into a PolicyMap, in parallel.
///
/// Each row is cut at the span boundaries of every lens over it (LensRegion::rowSpan). Between
/// two boundaries every lens is out, fully in or "edge" (coverage() decides per pixel). A
/// segment without edge lenses is one run of one lens set; only edge pixels evaluate coverage
/// and, when partly covered, blend. So the work grows with rows × lenses plus edge pixels, not
/// with the pixels the lenses cover.
///
/// Bands of rows are scanned in parallel; each numbers its lens sets in the order it meets
/// them. One thread then merges the bands in order: a set gets its policy the first time any
/// band met it, which is the order of a serial row-major scan, whatever the thread count. The
/// same pass appends every blend's terms and mix after the policies met before it, as serial
/// addPolicy and setPixelBlend calls would have, and the bands then fill their runs and point
/// their blended pixels at their mixes in parallel again.

#include <mvcl/lens/Lens.h>
#include <mvcl/lens/PixelPolicy.h>
#include <mvcl/lens/PolicyMap.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace mvcl {

using LensSnapshots = std::vector<std::shared_ptr<const LensSnapshot>>;

class PolicyMapComposer {
public:
    /// `snapshots` holds one snapshot per lens of the stack, bottom first: bit i of a lens set
    /// is snapshots[i]. Disabled lenses, lenses that change nothing and lenses off screen are
    /// left out.
    PolicyMapComposer(const LensSnapshots &snapshots, const RayPolicy &base, int width, int height);

    /// The map, on at most `threads` threads (0 = all cores); the same for any thread count.
    PolicyMap compose(int threads) const;

    /// The policy of pixels fully covered by exactly the lenses in `lensSet`, applied bottom →
    /// top onto `base`. Clip volumes that did not fit are counted in `*droppedClips`.
    static PixelPolicy policyOfSet(const LensSnapshots &snapshots, const RayPolicy &base, uint64_t lensSet,
                                   int *droppedClips = nullptr);

private:
    struct ActiveLens {
        int index;                // in the stack: its bit in a lens set
        PixelRect bounds;
        const LensRegion *region; // owned by the snapshot
    };
    class Band;

    void scanRow(int y, Band &band) const;
    void scanEdgePixels(int y, int x0, int x1, uint64_t fullSet, uint64_t edgeSet, Band &band) const;
    void mergeBands(std::vector<Band> &bands, PolicyMap &map) const;
    static void fillBand(const Band &band, PolicyMap &map);

    const LensSnapshots &m_snapshots;
    RayPolicy m_base;
    int m_width;
    int m_height;
    std::vector<ActiveLens> m_active;
    int m_firstRow = 0; // rows [m_firstRow, m_endRow) meet some active lens
    int m_endRow = 0;
};

} // namespace mvcl
