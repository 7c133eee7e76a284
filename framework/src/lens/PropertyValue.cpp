#include <mvcl/lens/PropertyValue.h>

#include "PropertyText_p.h"

#include <mvcl/core/Error.h>
#include <mvcl/model/LayerTable.h>

#include <vector>

namespace mvcl {

namespace {

constexpr const char *kRayTypeNames[kRayTypeCount] = {"primary", "shadow", "reflection",
                                                      "refraction"};

const char *articleFor(PropertyType type) {
    return type == PropertyType::Int ? "an" : "a";
}

std::vector<std::string_view> splitOnCommas(std::string_view text) {
    std::vector<std::string_view> parts;
    for (;;) {
        const size_t comma = text.find(',');
        parts.push_back(detail::trimmed(text.substr(0, comma)));
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return parts;
}

int parseLayerId(std::string_view text, std::string_view token) {
    int id = 0;
    if (!detail::parseWhole(text, id) || text.front() == '-')
        throw Error("", detail::quoted(token) +
                            " is not a layer id, a range a-b or an open range k- (layer k inward)");
    if (id < 0 || id >= kMaxLayers)
        throw Error("", "layer " + std::string(text) + " is outside 0.." +
                            std::to_string(kMaxLayers - 1));
    return id;
}

// Bits first..last inclusive.
uint32_t layerRange(int first, int last) {
    return layersFrom(first) & ~(last + 1 >= kMaxLayers ? 0u : layersFrom(last + 1));
}

} // namespace

const char *propertyTypeName(PropertyType type) {
    switch (type) {
    case PropertyType::Bool: return "bool";
    case PropertyType::Int: return "int";
    case PropertyType::Real: return "real";
    case PropertyType::Color: return "color";
    case PropertyType::Choice: return "choice";
    case PropertyType::LayerSet: return "layer set";
    case PropertyType::RayTypeSet: return "ray-type set";
    case PropertyType::Point3: return "point3";
    case PropertyType::Vector3: return "vector3";
    case PropertyType::Box3: return "box3";
    case PropertyType::Transform: return "transform";
    }
    return "unknown";
}

PropertyValue PropertyValue::boolean(bool value) {
    PropertyValue v(PropertyType::Bool);
    v.m_number = value ? 1.0 : 0.0;
    return v;
}

PropertyValue PropertyValue::integer(int value) {
    PropertyValue v(PropertyType::Int);
    v.m_number = value;
    return v;
}

PropertyValue PropertyValue::real(double value) {
    PropertyValue v(PropertyType::Real);
    v.m_number = value;
    return v;
}

PropertyValue PropertyValue::color(const glm::vec3 &value) {
    PropertyValue v(PropertyType::Color);
    for (int i = 0; i < 3; ++i) v.m_numbers[size_t(i)] = value[i];
    return v;
}

PropertyValue PropertyValue::point3(const glm::dvec3 &value) {
    PropertyValue v(PropertyType::Point3);
    for (int i = 0; i < 3; ++i) v.m_numbers[size_t(i)] = value[i];
    return v;
}

PropertyValue PropertyValue::vector3(const glm::dvec3 &value) {
    PropertyValue v(PropertyType::Vector3);
    for (int i = 0; i < 3; ++i) v.m_numbers[size_t(i)] = value[i];
    return v;
}

PropertyValue PropertyValue::box3(const Box3d &value) {
    PropertyValue v(PropertyType::Box3);
    for (int i = 0; i < 3; ++i) {
        v.m_numbers[size_t(i)] = value.min[i];
        v.m_numbers[size_t(i + 3)] = value.max[i];
    }
    return v;
}

PropertyValue PropertyValue::transform(const glm::dmat4 &value) {
    PropertyValue v(PropertyType::Transform);
    // Text order is row by row of [R | t]; glm is column-major (value[column][row]).
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column) v.m_numbers[size_t(row * 4 + column)] = value[column][row];
    return v;
}

PropertyValue PropertyValue::choice(std::string value) {
    PropertyValue v(PropertyType::Choice);
    v.m_text = std::move(value);
    return v;
}

PropertyValue PropertyValue::layerSet(uint32_t mask) {
    PropertyValue v(PropertyType::LayerSet);
    v.m_bits = mask;
    return v;
}

PropertyValue PropertyValue::rayTypeSet(uint8_t mask) {
    PropertyValue v(PropertyType::RayTypeSet);
    v.m_bits = mask;
    return v;
}

namespace {
void requireType(PropertyType actual, PropertyType wanted) {
    if (actual != wanted)
        throw Error("property value", std::string("holds ") + articleFor(actual) + " " +
                                          propertyTypeName(actual) + ", not " +
                                          articleFor(wanted) + " " + propertyTypeName(wanted));
}
} // namespace

bool PropertyValue::toBool() const {
    requireType(m_type, PropertyType::Bool);
    return m_number != 0.0;
}

int PropertyValue::toInt() const {
    requireType(m_type, PropertyType::Int);
    return int(m_number);
}

double PropertyValue::toReal() const {
    requireType(m_type, PropertyType::Real);
    return m_number;
}

glm::vec3 PropertyValue::toColor() const {
    requireType(m_type, PropertyType::Color);
    return glm::vec3(glm::dvec3(m_numbers[0], m_numbers[1], m_numbers[2]));
}

glm::dvec3 PropertyValue::toPoint3() const {
    requireType(m_type, PropertyType::Point3);
    return {m_numbers[0], m_numbers[1], m_numbers[2]};
}

glm::dvec3 PropertyValue::toVector3() const {
    requireType(m_type, PropertyType::Vector3);
    return {m_numbers[0], m_numbers[1], m_numbers[2]};
}

Box3d PropertyValue::toBox3() const {
    requireType(m_type, PropertyType::Box3);
    return {{m_numbers[0], m_numbers[1], m_numbers[2]}, {m_numbers[3], m_numbers[4], m_numbers[5]}};
}

glm::dmat4 PropertyValue::toTransform() const {
    requireType(m_type, PropertyType::Transform);
    glm::dmat4 m(1.0);
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column) m[column][row] = m_numbers[size_t(row * 4 + column)];
    return m;
}

std::vector<double> PropertyValue::components() const {
    size_t count = 0;
    switch (m_type) {
    case PropertyType::Color:
    case PropertyType::Point3:
    case PropertyType::Vector3: count = 3; break;
    case PropertyType::Box3: count = 6; break;
    case PropertyType::Transform: count = 12; break;
    default: break;
    }
    return {m_numbers.begin(), m_numbers.begin() + std::ptrdiff_t(count)};
}

const std::string &PropertyValue::toChoice() const {
    requireType(m_type, PropertyType::Choice);
    return m_text;
}

uint32_t PropertyValue::toLayerSet() const {
    requireType(m_type, PropertyType::LayerSet);
    return m_bits;
}

uint8_t PropertyValue::toRayTypeSet() const {
    requireType(m_type, PropertyType::RayTypeSet);
    return uint8_t(m_bits);
}

std::string PropertyValue::toString() const {
    switch (m_type) {
    case PropertyType::Bool: return m_number != 0.0 ? "true" : "false";
    case PropertyType::Int: return std::to_string(int(m_number));
    case PropertyType::Real: return detail::shortestText(m_number);
    case PropertyType::Color:
        // Colours are single precision: their shortest float text reads back exactly.
        return detail::shortestText(float(m_numbers[0])) + "," + detail::shortestText(float(m_numbers[1])) + "," +
               detail::shortestText(float(m_numbers[2]));
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3:
    case PropertyType::Transform: {
        std::string text;
        for (double number : components()) {
            if (!text.empty()) text += ',';
            text += detail::shortestText(number);
        }
        return text;
    }
    case PropertyType::Choice: return m_text;
    case PropertyType::LayerSet: return layerSetToString(m_bits);
    case PropertyType::RayTypeSet: return rayTypeSetToString(uint8_t(m_bits));
    }
    return {};
}

std::string layerSetToString(uint32_t mask) {
    if (mask == kAllLayers) return "all";
    if (mask == 0) return "none";
    std::string text;
    int id = 0;
    while (id < kMaxLayers) {
        if (!(mask & layerBit(id))) {
            ++id;
            continue;
        }
        int last = id;
        while (last + 1 < kMaxLayers && (mask & layerBit(last + 1))) ++last;
        if (!text.empty()) text += ',';
        text += std::to_string(id);
        // A run that reaches the innermost possible layer reads as "from layer k inward".
        if (last == kMaxLayers - 1 && last > id)
            text += '-';
        else if (last > id)
            text += '-' + std::to_string(last);
        id = last + 1;
    }
    return text;
}

uint32_t parseLayerSet(const std::string &text) {
    const std::string_view whole = detail::trimmed(text);
    const std::string keyword = detail::lowered(whole);
    if (keyword == "all") return kAllLayers;
    if (keyword == "none") return 0;
    uint32_t mask = 0;
    for (std::string_view token : splitOnCommas(whole)) {
        if (token.empty())
            throw Error("", detail::quoted(whole) + " has an empty entry; expected e.g. 0,2,5-7 or 2-");
        const size_t dash = token.find('-');
        if (dash == std::string_view::npos) {
            mask |= layerBit(parseLayerId(token, token));
            continue;
        }
        const std::string_view firstText = detail::trimmed(token.substr(0, dash));
        const std::string_view lastText = detail::trimmed(token.substr(dash + 1));
        const int first = parseLayerId(firstText, token);
        if (lastText.empty()) {
            mask |= layersFrom(first);
            continue;
        }
        const int last = parseLayerId(lastText, token);
        if (last < first)
            throw Error("", "layer range " + detail::quoted(token) + " runs backwards");
        mask |= layerRange(first, last);
    }
    return mask;
}

std::string rayTypeSetToString(uint8_t mask) {
    mask &= kAllRayTypes;
    if (mask == kAllRayTypes) return "all";
    if (mask == 0) return "none";
    std::string text;
    for (int type = 0; type < kRayTypeCount; ++type) {
        if (!(mask & rayTypeBit(RayType(type)))) continue;
        if (!text.empty()) text += ',';
        text += kRayTypeNames[type];
    }
    return text;
}

uint8_t parseRayTypeSet(const std::string &text) {
    const std::string_view whole = detail::trimmed(text);
    const std::string keyword = detail::lowered(whole);
    if (keyword == "all") return kAllRayTypes;
    if (keyword == "none") return 0;
    uint8_t mask = 0;
    for (std::string_view token : splitOnCommas(whole)) {
        const std::string name = detail::lowered(token);
        int type = 0;
        while (type < kRayTypeCount && name != kRayTypeNames[type]) ++type;
        if (type == kRayTypeCount)
            throw Error("", detail::quoted(token) +
                                " is not a ray type (all, none, or a list of primary, shadow, "
                                "reflection, refraction)");
        mask |= rayTypeBit(RayType(type));
    }
    return mask;
}

} // namespace mvcl
