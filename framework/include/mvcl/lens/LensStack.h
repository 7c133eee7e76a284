#pragma once
/// \file LensStack.h
/// An ordered stack of lenses (index 0 at the bottom) and its composition into a PolicyMap.
/// compose() reads committed lens snapshots only; it composes one policy per distinct overlap
/// set (per feathered term) and never per pixel, and pixels outside every lens keep the base
/// policy without any work.

#include <mvcl/core/Export.h>

#include <mvcl/lens/Lens.h>
#include <mvcl/lens/PolicyCost.h>
#include <mvcl/lens/PolicyMap.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mvcl {

/// Rendering cost of the pixels under one lens (pixels shared by overlapping lenses count for
/// each of them).
struct LensCost {
    int index = 0;     ///< position in the stack
    std::string label;
    uint64_t pixels = 0;
    uint64_t rays = 0;
    double milliseconds = 0.0;
};

class MVCL_EXPORT LensStack {
public:
    /// A stack holds at most this many lenses (one bit each in PixelPolicy::lensSet).
    static constexpr int kMaxLenses = 64;
    /// Partially covered (feathered) lenses blended exactly at one pixel; beyond this the
    /// weakest ones are rounded to fully in or out.
    static constexpr int kMaxBlendedLenses = 4;

    int size() const { return int(m_lenses.size()); }
    bool isEmpty() const { return m_lenses.empty(); }
    const std::shared_ptr<Lens> &lens(int index) const;
    const std::vector<std::shared_ptr<Lens>> &lenses() const { return m_lenses; }

    /// Puts a lens on top. Throws mvcl::Error for null or past kMaxLenses.
    void add(std::shared_ptr<Lens> lens);
    void insert(int index, std::shared_ptr<Lens> lens);
    void remove(int index);
    /// Moves the lens at `from` so that it ends up at `to`.
    void move(int from, int to);
    void clear() { m_lenses.clear(); }

    /// The policy map of a width × height view over `base`, composed on at most `threads`
    /// threads of the worker pool (0 = all cores). The map is the same for any thread count.
    /// Never throws for clip volumes that do not fit: see PolicyMap::droppedClipVolumes().
    PolicyMap compose(const RayPolicy &base, int width, int height, int threads = 0) const;
    /// The same with every lens as it is in `context` (Lens::snapshotIn), at the context's image
    /// size: what a render session shows.
    PolicyMap compose(const LensContext &context, const RayPolicy &base, int threads = 0) const;
    /// Throws mvcl::Error("lens stack", ...) naming the count when `map` (composed by this
    /// stack) left clip volumes out: for tools that must not render a wrong cut.
    static void checkClipVolumes(const PolicyMap &map);
    /// The policy of pixels fully covered by exactly the lenses in `lensSet` (bit i = lens i).
    PixelPolicy composeSet(const RayPolicy &base, uint64_t lensSet) const;

    /// Per-lens cost from a render of `map` (which this stack composed): `perPolicy[i]` is
    /// the cost of map policy i (RenderStats::perPolicy).
    std::vector<LensCost> costs(const PolicyMap &map, std::span<const PolicyCost> perPolicy) const;

private:
    std::vector<std::shared_ptr<Lens>> m_lenses;
};

} // namespace mvcl
