#include <mvcl/lens/PropertyDecl.h>

#include "PropertyText_p.h"

#include <mvcl/core/Error.h>

#include <algorithm>
#include <cmath>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

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

// `count` comma-separated numbers, optionally in brackets.
bool parseNumbers(std::string_view text, size_t count, std::vector<double> &numbers) {
    if (text.size() >= 2 && text.front() == '[' && text.back() == ']')
        text = detail::trimmed(text.substr(1, text.size() - 2));
    numbers.clear();
    for (;;) {
        const size_t comma = text.find(',');
        double number = 0.0;
        if (numbers.size() == count || !detail::parseWhole(detail::trimmed(text.substr(0, comma)), number) ||
            !std::isfinite(number))
            return false;
        numbers.push_back(number);
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return numbers.size() == count;
}

PropertyDecl spatial(std::string name, PropertyType type, PropertyValue defaultValue, PropertySpace space,
                     std::string unit, std::string doc) {
    PropertyDecl decl = declaration(std::move(name), type, std::move(defaultValue), std::move(doc));
    decl.space = space;
    decl.unit = std::move(unit);
    return decl;
}

const char *numbersExpected(PropertyType type) {
    switch (type) {
    case PropertyType::Point3: return "a point (x,y,z)";
    case PropertyType::Vector3: return "a vector (x,y,z)";
    case PropertyType::Box3: return "a box (minX,minY,minZ,maxX,maxY,maxZ)";
    default: return "an affine transform (identity, or 12 numbers: the rows of [R | t])";
    }
}

} // namespace

PropertyDecl PropertyDecl::point3(std::string name, const glm::dvec3 &defaultValue, PropertySpace space,
                                  std::string unit, std::string doc) {
    return spatial(std::move(name), PropertyType::Point3, PropertyValue::point3(defaultValue), space,
                   std::move(unit), std::move(doc));
}

PropertyDecl PropertyDecl::vector3(std::string name, const glm::dvec3 &defaultValue, PropertySpace space,
                                   std::string unit, std::string doc) {
    return spatial(std::move(name), PropertyType::Vector3, PropertyValue::vector3(defaultValue), space,
                   std::move(unit), std::move(doc));
}

PropertyDecl PropertyDecl::box3(std::string name, const Box3d &defaultValue, PropertySpace space, std::string unit,
                                std::string doc) {
    return spatial(std::move(name), PropertyType::Box3, PropertyValue::box3(defaultValue), space, std::move(unit),
                   std::move(doc));
}

PropertyDecl PropertyDecl::transform(std::string name, const glm::dmat4 &defaultValue, PropertySpace space,
                                     std::string doc) {
    return spatial(std::move(name), PropertyType::Transform, PropertyValue::transform(defaultValue), space, "",
                   std::move(doc));
}

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
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3:
    case PropertyType::Transform: {
        if (type == PropertyType::Transform && detail::lowered(text) == "identity") {
            value = PropertyValue::transform(glm::dmat4(1.0));
            break;
        }
        const size_t count = type == PropertyType::Box3 ? 6 : type == PropertyType::Transform ? 12 : 3;
        std::vector<double> n;
        if (!parseNumbers(text, count, n))
            throw Error(source, detail::quoted(text) + " is not " + numbersExpected(type));
        if (type == PropertyType::Point3) value = PropertyValue::point3({n[0], n[1], n[2]});
        if (type == PropertyType::Vector3) value = PropertyValue::vector3({n[0], n[1], n[2]});
        if (type == PropertyType::Box3) value = PropertyValue::box3({{n[0], n[1], n[2]}, {n[3], n[4], n[5]}});
        if (type == PropertyType::Transform) {
            glm::dmat4 m(1.0);
            for (int row = 0; row < 3; ++row)
                for (int column = 0; column < 4; ++column) m[column][row] = n[size_t(row * 4 + column)];
            value = PropertyValue::transform(m);
        }
        break;
    }
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
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3:
        for (double number : value.components()) checkRange(number, "component ");
        if (type == PropertyType::Box3) {
            const Box3d box = value.toBox3();
            for (int axis = 0; axis < 3; ++axis)
                if (box.min[axis] > box.max[axis])
                    throw Error(source, std::string("box minimum exceeds its maximum on ") + "xyz"[axis]);
        }
        break;
    case PropertyType::Transform: {
        for (double number : value.components())
            if (!std::isfinite(number))
                throw Error(source, "component " + detail::shortestText(number) + " is not a finite number");
        const glm::dmat4 m = value.toTransform();
        if (!(std::abs(glm::determinant(glm::dmat3(m))) > 1e-12))
            throw Error(source, "the transform's linear part is not invertible");
        break;
    }
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
    case PropertyType::Transform:
        return "affine (identity or 12 numbers), " + spaceText();
    case PropertyType::Int:
    case PropertyType::Real:
    case PropertyType::Color:
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3: {
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
        if (type == PropertyType::Point3 || type == PropertyType::Vector3 || type == PropertyType::Box3) {
            text += " per component, ";
            text += spaceText();
        }
        return text;
    }
    case PropertyType::Choice: return "one of " + joined(choices, "|");
    case PropertyType::LayerSet: return "all|none|ids and ranges such as 0,2,5-7|k- (layer k inward)";
    case PropertyType::RayTypeSet: return "all|none|list of primary,shadow,reflection,refraction";
    }
    return {};
}

std::string PropertyDecl::spaceText() const {
    if (spaceFrom.property.empty()) return std::string(propertySpaceName(space)) + " space";
    std::string text = "space by " + spaceFrom.property + " (";
    for (size_t i = 0; i < spaceFrom.spaces.size(); ++i) {
        if (i > 0) text += ", ";
        text += spaceFrom.spaces[i].first + ": " + propertySpaceName(spaceFrom.spaces[i].second);
    }
    return text + ")";
}

PropertyDecl PropertyDecl::withSpaceFrom(std::string choice,
                                         std::vector<std::pair<std::string, PropertySpace>> spaces) const {
    PropertyDecl decl = *this;
    decl.spaceFrom = {std::move(choice), std::move(spaces)};
    return decl;
}

PropertyDecl PropertyDecl::whenChoice(std::string choice, std::string value) const {
    PropertyDecl decl = *this;
    decl.usedWhen = {std::move(choice), std::move(value)};
    return decl;
}

const PropertyDecl *findProperty(const PropertyTable &table, std::string_view name) {
    for (const PropertyDecl &decl : table)
        if (decl.name == name) return &decl;
    return nullptr;
}

} // namespace mvcl
