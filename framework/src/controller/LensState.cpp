#include <mvcl/controller/LensState.h>

#include <mvcl/core/Error.h>
#include <mvcl/lens/Lens.h>
#include <mvcl/lens/LensRegistry.h>

namespace mvcl {

LensState LensState::of(const Lens &lens) {
    const std::shared_ptr<const LensSnapshot> snapshot = lens.snapshot();
    LensState state;
    state.type = lens.typeName();
    state.label = lens.label();
    state.enabled = snapshot->enabled;
    state.region = snapshot->region;
    const std::vector<PropertyValue> values = lens.committedValues();
    const PropertyTable &table = lens.properties();
    for (std::size_t i = 0; i < values.size() && i < table.size(); ++i)
        state.properties.emplace_back(table[i].name, values[i].toString());
    return state;
}

std::shared_ptr<Lens> LensState::create(const LensRegistry &registry) const {
    std::shared_ptr<Lens> lens = registry.create(type);
    applyTo(*lens);
    return lens;
}

void LensState::applyTo(Lens &lens) const {
    if (lens.typeName() != type)
        throw Error("lens '" + lens.label() + "'", "is a " + lens.typeName() + " lens, not a " + type + " lens");
    lens.setLabel(label);
    lens.setEnabled(enabled);
    lens.setRegion(region);
    lens.resetProperties();
    for (const auto &[name, text] : properties) lens.setPropertyText(name, text);
    lens.commit();
}

} // namespace mvcl
