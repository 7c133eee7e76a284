#include <mvcl/model/LayerContact.h>

#include <mvcl/core/Error.h>
#include <mvcl/core/FloatBits.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mvcl {

float LayerContact::sceneUnits(const Bounds3f &sceneBounds) const {
    if (!isEnabled()) return 0.f;
    if (measure == Measure::SceneUnits) return float(distance);
    if (sceneBounds.isEmpty()) return 0.f;
    // In double, each product on its own: the result must not depend on FMA contraction.
    const glm::dvec3 e(sceneBounds.extent());
    const double products[3] = {unfused(e.x * e.x), unfused(e.y * e.y), unfused(e.z * e.z)};
    return float(distance * std::sqrt(products[0] + products[1] + products[2]));
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
