#pragma once
/// \file LensState.h
/// Everything that makes one lens what it is, as plain values: its type, label, committed
/// enabled flag, region and property values in their canonical text. Undo steps store these
/// rather than lens objects, so a restored lens is built afresh from text exactly as a
/// session file builds it.

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensRegion.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mvcl {

class Lens;
class LensRegistry;

struct MVCL_EXPORT LensState {
    std::string type;
    std::string label;
    bool enabled = true;
    LensRegion region;
    /// (name, canonical text) in the lens's property-table order.
    std::vector<std::pair<std::string, std::string>> properties;

    /// The lens's committed state (what renders), not its staged edits.
    static LensState of(const Lens &lens);
    /// A new lens of `type` from `registry` in this state, committed. Throws mvcl::Error when
    /// the type is unknown or a value does not parse.
    std::shared_ptr<Lens> create(const LensRegistry &registry) const;
    /// Sets `lens` (of this type) to this state and commits it.
    void applyTo(Lens &lens) const;

    bool operator==(const LensState &other) const = default;
};

} // namespace mvcl
