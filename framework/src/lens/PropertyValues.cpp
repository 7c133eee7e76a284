#include <mvcl/lens/PropertyValues.h>

#include <mvcl/core/Error.h>

#include <algorithm>

namespace mvcl {

PropertyValues::PropertyValues(const PropertyTable &table, const std::vector<PropertyValue> &values)
    : m_table(table), m_values(values), m_read(table.size(), false) {
    if (values.size() != table.size())
        throw Error("lens properties", std::to_string(values.size()) + " values for " +
                                           std::to_string(table.size()) + " declarations");
}

const PropertyValue &PropertyValues::value(std::string_view name) const {
    for (size_t i = 0; i < m_table.size(); ++i) {
        if (m_table[i].name != name) continue;
        m_read[i] = true;
        return m_values[i];
    }
    throw Error("lens properties", "no property '" + std::string(name) + "' is declared");
}

namespace {
// Re-throws a type mismatch naming the property the lens asked for.
template <typename Read> decltype(auto) typedRead(std::string_view name, Read read) {
    try {
        return read();
    } catch (const Error &e) {
        if (e.source() != "property value") throw;
        throw Error("property '" + std::string(name) + "'", e.problem());
    }
}
} // namespace

bool PropertyValues::boolean(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toBool(); });
}

int PropertyValues::integer(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toInt(); });
}

double PropertyValues::real(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toReal(); });
}

glm::vec3 PropertyValues::color(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toColor(); });
}

const std::string &PropertyValues::choice(std::string_view name) const {
    return typedRead(name, [&]() -> const std::string & { return value(name).toChoice(); });
}

int PropertyValues::choiceIndex(std::string_view name) const {
    const std::string &chosen = choice(name);
    const std::vector<std::string> &choices = declaration(name).choices;
    return int(std::find(choices.begin(), choices.end(), chosen) - choices.begin());
}

uint32_t PropertyValues::layers(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toLayerSet(); });
}

uint8_t PropertyValues::rayTypes(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toRayTypeSet(); });
}

glm::dvec3 PropertyValues::point3(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toPoint3(); });
}

glm::dvec3 PropertyValues::vector3(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toVector3(); });
}

Box3d PropertyValues::box3(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toBox3(); });
}

glm::dmat4 PropertyValues::transform(std::string_view name) const {
    return typedRead(name, [&] { return value(name).toTransform(); });
}

const PropertyDecl &PropertyValues::declaration(std::string_view name) const {
    for (const PropertyDecl &decl : m_table)
        if (decl.name == name) return decl;
    throw Error("lens properties", "no property '" + std::string(name) + "' is declared");
}

PropertySpace PropertyValues::space(std::string_view name) const {
    const PropertyDecl &decl = declaration(name);
    if (decl.spaceFrom.property.empty()) return decl.space;
    const std::string &chosen = choice(decl.spaceFrom.property);
    for (const auto &[value, space] : decl.spaceFrom.spaces)
        if (value == chosen) return space;
    return decl.space; // a choice the declaration maps to nothing keeps the declared space
}

bool PropertyValues::isUsed(std::string_view name) const {
    const PropertyDecl &decl = declaration(name);
    return decl.usedWhen.property.empty() || value(decl.usedWhen.property).toChoice() == decl.usedWhen.value;
}

std::vector<std::string> PropertyValues::unreadNames() const {
    std::vector<std::string> names;
    for (size_t i = 0; i < m_table.size(); ++i)
        if (!m_read[i]) names.push_back(m_table[i].name);
    return names;
}

} // namespace mvcl
