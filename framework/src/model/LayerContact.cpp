#include <mvcl/model/LayerContact.h>

#include <mvcl/core/Error.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mvcl {

float LayerContact::sceneUnits(const Bounds3f &sceneBounds) const {
    if (!isEnabled()) return 0.f;
    if (measure == Measure::SceneUnits) return float(distance);
    if (sceneBounds.isEmpty()) return 0.f;
    return float(distance * double(glm::length(sceneBounds.extent())));
}

LayerContact LayerContact::parse(const std::string &text) {
    const char *begin = text.c_str();
    char *end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin) throw Error("layer contact", "'" + text + "' is not a number");
    std::string rest(end);
    while (!rest.empty() && rest.front() == ' ') rest.erase(rest.begin());
    LayerContact contact;
    if (rest == "units") contact.measure = Measure::SceneUnits;
    else if (!rest.empty())
        throw Error("layer contact", "'" + text + "': expected a number (relative to the scene's size) or a number followed by 'units'");
    if (!std::isfinite(value) || value < 0.0)
        throw Error("layer contact", "'" + text + "': the tolerance must be finite and not negative");
    contact.distance = value;
    return contact;
}

std::string LayerContact::toString() const {
    if (!isEnabled()) return "0";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6g%s", distance, measure == Measure::SceneUnits ? " units" : "");
    return buf;
}

} // namespace mvcl
