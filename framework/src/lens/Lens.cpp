#include <mvcl/lens/Lens.h>

#include <mvcl/core/Error.h>

#include <algorithm>
#include <exception>
#include <mutex>

namespace mvcl {

namespace {
constexpr const char *kRaysProperty = "rays";
} // namespace

/// Lens state behind the d-pointer, so plugins built against one framework version keep the
/// same sizeof(Lens) when this grows.
class LensPrivate {
public:
    explicit LensPrivate(const LensInfo &lensInfo) : info(lensInfo), label(lensInfo.name) {
        source = "lens '" + info.name + "'";
        if (info.name.empty()) throw Error("lens", "the lens type has no name");
        properties = info.properties;
        properties.push_back(PropertyDecl::rayTypes(kRaysProperty, info.defaultRayTypes,
                                                    "ray types the lens acts on"));
        for (size_t i = 0; i < properties.size(); ++i) {
            const PropertyDecl &decl = properties[i];
            if (decl.name.empty()) throw Error(source, "declares a property without a name");
            if (i + 1 < properties.size() && decl.name == kRaysProperty)
                throw Error(source, "declares 'rays' itself; every lens has it already (set "
                                    "LensInfo::defaultRayTypes instead)");
            for (size_t j = 0; j < i; ++j)
                if (properties[j].name == decl.name)
                    throw Error(source, "declares property '" + decl.name + "' twice");
            try {
                decl.validate(decl.defaultValue);
            } catch (const Error &e) {
                throw Error(source, std::string("default of ") + e.what());
            }
            defaults.push_back(decl.defaultValue);
        }
        stagedValues = defaults;
        committedValues = defaults;
        snapshot = std::make_shared<const LensSnapshot>();
    }

    /// Index of `name` in `properties`; throws naming the lens and the known keys otherwise.
    size_t indexOf(std::string_view name) const {
        for (size_t i = 0; i < properties.size(); ++i)
            if (properties[i].name == name) return i;
        std::string known;
        for (const PropertyDecl &decl : properties) known += (known.empty() ? "" : ", ") + decl.name;
        throw Error(source, "unknown property '" + std::string(name) + "' (known: " + known + ")");
    }

    /// Re-throws `e` so that its message names this lens exactly once.
    [[noreturn]] void rethrowNamingLens(const Error &e) const {
        if (e.source() == source) throw e;
        throw Error(source, e.what());
    }

    const LensInfo info;
    std::string source; ///< "lens '<type>'", the source of every error this lens reports
    PropertyTable properties;
    std::vector<PropertyValue> defaults;
    std::string label;

    /// Whether a contribution made in `a` may differ from one made in `b` for this lens.
    bool contextsDiffer(const LensContext &a, const LensContext &b) const {
        return !a.sameScene(b) || (info.dependsOnView && !a.sameView(b));
    }

    /// The contribution of `values` and `region` in `context`, checked and restricted to the
    /// lens's "rays"; throws mvcl::Error naming the lens. `unread` gets the unread names.
    LensContribution contribution(const Lens &lens, const std::vector<PropertyValue> &values, const LensRegion &region,
                                  const LensContext &context, std::vector<std::string> *unread) const {
        LensContribution result;
        try {
            region.validate();
            const PropertyValues read(properties, values);
            result = lens.contribute(read, region, context);
            result.validate();
            if (unread) *unread = read.unreadNames();
        } catch (const Error &e) {
            rethrowNamingLens(e);
        } catch (const std::exception &e) {
            throw Error(source, std::string("contribute() failed: ") + e.what());
        } catch (...) {
            throw Error(source, "contribute() failed with an unknown exception");
        }
        return result.restrictedTo(values.back().toRayTypeSet());
    }

    /// Publishes the staged state with `contribution` as the next snapshot.
    void publish(const LensContribution &contribution, std::vector<std::string> unread, std::string newFault) {
        // "rays" is applied here, not by the plugin, so it never counts as unread.
        std::erase(unread, std::string(kRaysProperty));
        auto next = std::make_shared<LensSnapshot>();
        next->enabled = stagedEnabled;
        next->region = stagedRegion;
        next->contribution = contribution;
        next->idempotent = info.algebra.idempotent;

        const std::lock_guard lock(committedMutex);
        next->version = snapshot->version + 1;
        snapshot = std::move(next);
        committedValues = stagedValues;
        committedContext = stagedContext;
        unreadProperties = std::move(unread);
        fault = std::move(newFault);
    }

    // Staged state; edited by one thread at a time.
    bool stagedEnabled = true;
    LensRegion stagedRegion;
    std::vector<PropertyValue> stagedValues;
    LensContext stagedContext;

    // Committed state; read by render threads, so guarded.
    mutable std::mutex committedMutex;
    std::shared_ptr<const LensSnapshot> snapshot;
    std::vector<PropertyValue> committedValues;
    LensContext committedContext;
    std::vector<std::string> unreadProperties;
    std::string fault; ///< the last refused contribution's error, empty when sound
    // The last snapshotIn() that had to re-contribute: for committed version `inContextVersion`
    // in `inContext`.
    std::shared_ptr<const LensSnapshot> inContextSnapshot;
    uint64_t inContextVersion = 0;
    LensContext inContext;
};

Lens::Lens(const LensInfo &info) : d(std::make_unique<LensPrivate>(info)) {}

Lens::~Lens() = default;

const LensInfo &Lens::info() const { return d->info; }
const std::string &Lens::typeName() const { return d->info.name; }
const PropertyTable &Lens::properties() const { return d->properties; }

const std::string &Lens::label() const { return d->label; }
void Lens::setLabel(std::string label) { d->label = std::move(label); }

bool Lens::isEnabled() const { return d->stagedEnabled; }
void Lens::setEnabled(bool enabled) { d->stagedEnabled = enabled; }

const LensRegion &Lens::region() const { return d->stagedRegion; }
void Lens::setRegion(const LensRegion &region) { d->stagedRegion = region; }

const LensContext &Lens::context() const { return d->stagedContext; }
void Lens::setContext(const LensContext &context) { d->stagedContext = context; }

PropertyValue Lens::property(std::string_view name) const {
    return d->stagedValues[d->indexOf(name)];
}

void Lens::setProperty(std::string_view name, const PropertyValue &value) {
    const size_t index = d->indexOf(name);
    try {
        d->properties[index].validate(value);
    } catch (const Error &e) {
        d->rethrowNamingLens(e);
    }
    d->stagedValues[index] = value;
}

void Lens::setPropertyText(std::string_view name, std::string_view text) {
    const size_t index = d->indexOf(name);
    try {
        d->stagedValues[index] = d->properties[index].parse(text);
    } catch (const Error &e) {
        d->rethrowNamingLens(e);
    }
}

void Lens::resetProperties() { d->stagedValues = d->defaults; }

bool Lens::hasUncommittedChanges() const {
    const std::lock_guard lock(d->committedMutex);
    return d->snapshot->version == 0 || d->stagedEnabled != d->snapshot->enabled ||
           !(d->stagedRegion == d->snapshot->region) || d->stagedValues != d->committedValues ||
           d->contextsDiffer(d->stagedContext, d->committedContext);
}

void Lens::commit() {
    std::vector<std::string> unread;
    const LensContribution contribution =
        d->contribution(*this, d->stagedValues, d->stagedRegion, d->stagedContext, &unread);
    d->publish(contribution, std::move(unread), {});
}

void Lens::commitOrDisable() {
    try {
        d->stagedRegion.validate();
    } catch (const Error &e) {
        d->rethrowNamingLens(e);
    }
    std::vector<std::string> unread;
    try {
        const LensContribution contribution =
            d->contribution(*this, d->stagedValues, d->stagedRegion, d->stagedContext, &unread);
        d->publish(contribution, std::move(unread), {});
    } catch (const Error &e) {
        d->stagedEnabled = false;
        d->publish(LensContribution{}, {}, e.what());
    }
}

std::string Lens::fault() const {
    const std::lock_guard lock(d->committedMutex);
    return d->fault;
}

std::shared_ptr<const LensSnapshot> Lens::snapshotIn(const LensContext &context) const {
    const std::lock_guard lock(d->committedMutex);
    if (d->snapshot->version == 0 || !d->contextsDiffer(context, d->committedContext)) return d->snapshot;
    if (d->inContextSnapshot && d->inContextVersion == d->snapshot->version &&
        !d->contextsDiffer(context, d->inContext))
        return d->inContextSnapshot;
    auto next = std::make_shared<LensSnapshot>(*d->snapshot);
    try {
        next->contribution = d->contribution(*this, d->committedValues, next->region, context, nullptr);
    } catch (const Error &e) {
        // It committed in its own context; in this one it cannot say what it wants: no effect.
        next->enabled = false;
        next->contribution = LensContribution{};
        d->fault = e.what();
    }
    d->inContextSnapshot = std::move(next);
    d->inContextVersion = d->snapshot->version;
    d->inContext = context;
    return d->inContextSnapshot;
}

std::shared_ptr<const LensSnapshot> Lens::snapshot() const {
    const std::lock_guard lock(d->committedMutex);
    return d->snapshot;
}

std::vector<PropertyValue> Lens::committedValues() const {
    const std::lock_guard lock(d->committedMutex);
    return d->committedValues;
}

std::vector<std::string> Lens::unreadProperties() const {
    const std::lock_guard lock(d->committedMutex);
    return d->unreadProperties;
}

} // namespace mvcl
