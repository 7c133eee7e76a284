#pragma once
/// \file Lens.h
/// The lens plugin interface. A lens is a region on the screen, a policy contribution and
/// properties. Setters stage; commit() validates and publishes an immutable snapshot; the lens
/// stack and the renderer only ever read committed snapshots, so a UI thread may edit a lens
/// while a frame renders.
///
/// A plugin derives from Lens, passes its static LensInfo to the constructor and implements
/// contribute(). Every lens also has the common property "rays" (which ray types it acts on;
/// its default comes from LensInfo::defaultRayTypes).
///
/// contribute() sees a LensContext (camera, image size, scene bounds, world origin, layers).
/// commit() passes the staged context (setContext); a render session asks for snapshotIn() its
/// own context, which re-runs contribute() on the committed values only when the context
/// differs in what the lens depends on (the scene always, the view if LensInfo::dependsOnView).

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensContext.h>
#include <mvcl/lens/LensContribution.h>
#include <mvcl/lens/LensInfo.h>
#include <mvcl/lens/LensRegion.h>
#include <mvcl/lens/PropertyValues.h>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace mvcl {

/// What the renderer sees of a lens: immutable, shared, replaced as a whole on commit().
struct LensSnapshot {
    uint64_t version = 0; ///< 0 before the first commit; +1 per commit
    bool enabled = false;
    LensRegion region;
    /// Already restricted to the lens's "rays".
    LensContribution contribution;
    /// LensInfo::algebra.idempotent: the stack composes an equal lens right above this one as
    /// one lens, feathered edges included.
    bool idempotent = false;
};

class LensPrivate;

class MVCL_EXPORT Lens {
public:
    /// `info` is copied. The lens starts on its defaults, uncommitted (snapshot disabled).
    explicit Lens(const LensInfo &info);
    virtual ~Lens();
    Lens(const Lens &) = delete;
    Lens &operator=(const Lens &) = delete;

    const LensInfo &info() const;
    const std::string &typeName() const;
    /// The declared parameters plus the common "rays".
    const PropertyTable &properties() const;

    /// A user-facing label for stats and UIs; defaults to the type name.
    const std::string &label() const;
    void setLabel(std::string label);

    // --- staged state: takes effect on commit() ---
    bool isEnabled() const;
    void setEnabled(bool enabled);
    const LensRegion &region() const;
    void setRegion(const LensRegion &region);
    /// The scene and view the next commit() builds the contribution in.
    const LensContext &context() const;
    void setContext(const LensContext &context);
    /// Staged value of a declared property; throws mvcl::Error naming the lens for unknown keys.
    PropertyValue property(std::string_view name) const;
    /// Stages a value; throws mvcl::Error for unknown keys, a wrong type or out-of-range values.
    void setProperty(std::string_view name, const PropertyValue &value);
    /// Parses text with the property's declaration (files, command line).
    void setPropertyText(std::string_view name, std::string_view text);
    /// Every staged property back to its declared default.
    void resetProperties();
    bool hasUncommittedChanges() const;

    /// Validates the staged state, builds the contribution in the staged context, checks it
    /// (LensContribution::validate: finite numbers, valid clip volumes, ranges) and publishes a
    /// new snapshot. On error throws mvcl::Error naming the lens and keeps the previous snapshot:
    /// an edit that cannot be committed is refused, and the lens goes on as it was.
    void commit();
    /// commit() for a lens that must exist whatever its plugin does (a new lens, a lens read
    /// from a file): when the plugin's contribution fails (contribute() throws, or returns
    /// non-finite numbers, out-of-range values or a malformed map), the lens is disabled instead
    /// (staged and committed, with the staged values and region kept, so that files keep them)
    /// and fault() says why. Only an invalid region still throws.
    void commitOrDisable();
    /// Why the plugin's contribution was refused, naming the lens and the problem ("lens 'x':
    /// contribute() failed: ..."), or empty. Set by commitOrDisable() and by snapshotIn() (a
    /// contribution that fails in a session's context); cleared by the next commit whose
    /// contribution is sound. Any thread.
    std::string fault() const;
    /// The last committed state; never null.
    std::shared_ptr<const LensSnapshot> snapshot() const;
    /// The last committed state as it is in `context`: snapshot() itself when `context` agrees
    /// with the committed one in what this lens depends on (scene; view too if
    /// LensInfo::dependsOnView), else the committed values and region re-contributed in
    /// `context` (the last such result is kept, so equal contexts give the same pointer). Any
    /// thread; never throws: a contribution that fails in `context` gives a disabled snapshot
    /// and sets fault().
    std::shared_ptr<const LensSnapshot> snapshotIn(const LensContext &context) const;
    /// Committed property values in table order (for files and round trips).
    std::vector<PropertyValue> committedValues() const;
    /// Declared parameters the last commit's contribute() did not read (a plugin bug).
    std::vector<std::string> unreadProperties() const;

protected:
    /// Builds the lens's contribution from committed values in `context`. Called by commit()
    /// and by snapshotIn(), on any thread; must not depend on anything but its arguments.
    /// Reading the camera or image size from `context` requires LensInfo::dependsOnView.
    virtual LensContribution contribute(const PropertyValues &properties, const LensRegion &region,
                                        const LensContext &context) const = 0;

private:
    friend class LensPrivate; // calls contribute() for commit() and snapshotIn()
    std::unique_ptr<LensPrivate> d;
};

} // namespace mvcl
