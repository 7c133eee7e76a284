#include <mvcl/lens/PropertyDecl.h>

#include "PropertyText_p.h"

#include <mvcl/core/Error.h>

#include <algorithm>
#include <cmath>

namespace mvcl {

namespace {

PropertyDecl declaration(std::string name, PropertyType type, PropertyValue defaultValue,
                         std::string doc) {
    PropertyDecl decl;
    decl.name = std::move(name);
    decl.type = type;
    decl.defaultValue = std::move(defaultValue);
    decl.doc = std::move(doc);
    return decl;
}

std::string joined(const std::vector<std::string> &items, const char *separator) {
    std::string text;
    for (const std::string &item : items) {
        if (!text.empty()) text += separator;
        text += item;
    }
    return text;
}

bool parseBool(std::string_view text, bool &value) {
    const std::string word = detail::lowered(text);
    if (word == "true" || word == "1" || word == "on" || word == "yes") {
        value = true;
        return true;
    }
    if (word == "false" || word == "0" || word == "off" || word == "no") {
        value = false;
        return true;
    }
    return false;
}

// "r,g,b", "[r,g,b]" or one grey value.
bool parseColor(std::string_view text, glm::vec3 &value) {
    if (text.size() >= 2 && text.front() == '[' && text.back() == ']')
        text = detail::trimmed(text.substr(1, text.size() - 2));
    float components[3] = {0.f, 0.f, 0.f};
    int count = 0;
    for (;;) {
        const size_t comma = text.find(',');
        if (count == 3) return false;
        const std::string_view part = detail::trimmed(text.substr(0, comma));
        if (!detail::parseWhole(part, components[count])) return false;
        ++count;
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    if (count == 1) {
        value = glm::vec3(components[0]);
        return true;
    }
    if (count != 3) return false;
    value = glm::vec3(components[0], components[1], components[2]);
    return true;
}

} // namespace

PropertyDecl PropertyDecl::boolean(std::string name, bool defaultValue, std::string doc) {
    return declaration(std::move(name), PropertyType::Bool, PropertyValue::boolean(defaultValue),
                       std::move(doc));
}

PropertyDecl PropertyDecl::integer(std::string name, int defaultValue, int minimum, int maximum,
                                   std::string unit, std::string doc) {
    PropertyDecl decl = declaration(std::move(name), PropertyType::Int,
                                    PropertyValue::integer(defaultValue), std::move(doc));
    decl.minimum = minimum;
    decl.maximum = maximum;
    decl.unit = std::move(unit);
    return decl;
}

PropertyDecl PropertyDecl::real(std::string name, double defaultValue, double minimum,
                                double maximum, std::string unit, std::string doc) {
    PropertyDecl decl = declaration(std::move(name), PropertyType::Real,
                                    PropertyValue::real(defaultValue), std::move(doc));
    decl.minimum = minimum;
    decl.maximum = maximum;
    decl.unit = std::move(unit);
    return decl;
}

PropertyDecl PropertyDecl::color(std::string name, const glm::vec3 &defaultValue,
                                 std::string doc) {
    PropertyDecl decl = declaration(std::move(name), PropertyType::Color,
                                    PropertyValue::color(defaultValue), std::move(doc));
    decl.minimum = 0.0;
    return decl;
}

PropertyDecl PropertyDecl::choice(std::string name, std::string defaultValue,
                                  std::vector<std::string> choices, std::string doc) {
    PropertyDecl decl =
        declaration(std::move(name), PropertyType::Choice,
                    PropertyValue::choice(std::move(defaultValue)), std::move(doc));
    decl.choices = std::move(choices);
    return decl;
}

PropertyDecl PropertyDecl::layers(std::string name, uint32_t defaultMask, std::string doc) {
    return declaration(std::move(name), PropertyType::LayerSet,
                       PropertyValue::layerSet(defaultMask), std::move(doc));
}

PropertyDecl PropertyDecl::rayTypes(std::string name, uint8_t defaultMask, std::string doc) {
    return declaration(std::move(name), PropertyType::RayTypeSet,
                       PropertyValue::rayTypeSet(defaultMask), std::move(doc));
}

PropertyValue PropertyDecl::parse(std::string_view rawText) const {
    const std::string source = "property '" + name + "'";
    const std::string_view text = detail::trimmed(rawText);
    PropertyValue value;
    switch (type) {
    case PropertyType::Bool: {
        bool flag = false;
        if (!parseBool(text, flag))
            throw Error(source, detail::quoted(text) + " is not true or false");
        value = PropertyValue::boolean(flag);
        break;
    }
    case PropertyType::Int: {
        int number = 0;
        if (!detail::parseWhole(text, number))
            throw Error(source, detail::quoted(text) + " is not an integer");
        value = PropertyValue::integer(number);
        break;
    }
    case PropertyType::Real: {
        double number = 0.0;
        if (!detail::parseWhole(text, number) || !std::isfinite(number))
            throw Error(source, detail::quoted(text) + " is not a number");
        value = PropertyValue::real(number);
        break;
    }
    case PropertyType::Color: {
        glm::vec3 rgb(0.f);
        if (!parseColor(text, rgb) || !std::isfinite(rgb.r) || !std::isfinite(rgb.g) ||
            !std::isfinite(rgb.b))
            throw Error(source, detail::quoted(text) + " is not a colour (r,g,b or one grey value)");
        value = PropertyValue::color(rgb);
        break;
    }
    case PropertyType::Choice: value = PropertyValue::choice(std::string(text)); break;
    case PropertyType::LayerSet:
    case PropertyType::RayTypeSet:
        // The set parsers throw Error("", problem); name this property as the source instead.
        try {
            const std::string textCopy(text);
            value = type == PropertyType::LayerSet ? PropertyValue::layerSet(parseLayerSet(textCopy))
                                                   : PropertyValue::rayTypeSet(parseRayTypeSet(textCopy));
        } catch (const Error &e) {
            throw Error(source, e.problem());
        }
        break;
    }
    validate(value);
    return value;
}

void PropertyDecl::validate(const PropertyValue &value) const {
    const std::string source = "property '" + name + "'";
    if (value.type() != type)
        throw Error(source, std::string("expects a value of type ") + propertyTypeName(type) +
                                ", got " + propertyTypeName(value.type()));
    const auto checkRange = [&](double number, const char *what) {
        if (!std::isfinite(number))
            throw Error(source, std::string(what) + detail::shortestText(number) +
                                    " is not a finite number");
        if (number < minimum || number > maximum)
            throw Error(source, std::string(what) + detail::shortestText(number) +
                                    " is outside " + rangeText());
    };
    switch (type) {
    case PropertyType::Bool: break;
    case PropertyType::Int: checkRange(value.toInt(), ""); break;
    case PropertyType::Real: checkRange(value.toReal(), ""); break;
    case PropertyType::Color: {
        const glm::vec3 rgb = value.toColor();
        for (int i = 0; i < 3; ++i) checkRange(rgb[i], "colour component ");
        break;
    }
    case PropertyType::Choice:
        if (std::find(choices.begin(), choices.end(), value.toChoice()) == choices.end())
            throw Error(source, detail::quoted(value.toChoice()) + " is not one of " +
                                    joined(choices, "|"));
        break;
    case PropertyType::LayerSet: break; // every 32-bit mask is a valid set of layers
    case PropertyType::RayTypeSet:
        if (value.toRayTypeSet() & ~kAllRayTypes)
            throw Error(source, "ray-type mask " + std::to_string(value.toRayTypeSet()) +
                                    " has bits beyond the " + std::to_string(kRayTypeCount) +
                                    " ray types");
        break;
    }
}

std::string PropertyDecl::rangeText() const {
    switch (type) {
    case PropertyType::Bool: return "true|false";
    case PropertyType::Int:
    case PropertyType::Real:
    case PropertyType::Color: {
        // An infinite bound is open: "[0, ∞)".
        std::string text(std::isinf(minimum) ? "(" : "[");
        text += detail::boundText(minimum);
        text += ", ";
        text += detail::boundText(maximum);
        text += std::isinf(maximum) ? ")" : "]";
        if (!unit.empty()) {
            text += ' ';
            text += unit;
        }
        return text;
    }
    case PropertyType::Choice: return "one of " + joined(choices, "|");
    case PropertyType::LayerSet: return "all|none|ids and ranges such as 0,2,5-7|k- (layer k inward)";
    case PropertyType::RayTypeSet: return "all|none|list of primary,shadow,reflection,refraction";
    }
    return {};
}

const PropertyDecl *findProperty(const PropertyTable &table, std::string_view name) {
    for (const PropertyDecl &decl : table)
        if (decl.name == name) return &decl;
    return nullptr;
}

} // namespace mvcl
