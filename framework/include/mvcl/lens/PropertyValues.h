#pragma once
/// \file PropertyValues.h
/// The committed values a lens builds its contribution from. Reading is by name and typed;
/// it remembers which names were read so the conformance suite can report parameters a lens
/// declares but never uses (Mitsuba's "unreferenced property" check).

#include <mvcl/core/Export.h>

#include <mvcl/lens/PropertyDecl.h>

#include <string>
#include <string_view>
#include <vector>

namespace mvcl {

class MVCL_EXPORT PropertyValues {
public:
    /// `values[i]` belongs to `table[i]`; both must outlive this object.
    PropertyValues(const PropertyTable &table, const std::vector<PropertyValue> &values);

    /// Typed reads; each throws mvcl::Error if `name` is not declared or has another type.
    bool boolean(std::string_view name) const;
    int integer(std::string_view name) const;
    double real(std::string_view name) const;
    glm::vec3 color(std::string_view name) const;
    const std::string &choice(std::string_view name) const;
    /// Position of the choice among the declared choices (0 = the first): maps a choice onto an
    /// enum declared in the same order, e.g. ClipVolume::CapStyle(choiceIndex("caps")).
    int choiceIndex(std::string_view name) const;
    uint32_t layers(std::string_view name) const;
    uint8_t rayTypes(std::string_view name) const;
    /// Spatial values as declared (in their declaration's space); LensContext::scenePoint and
    /// its siblings turn them into scene space, PropertyDecl::space says which space.
    glm::dvec3 point3(std::string_view name) const;
    glm::dvec3 vector3(std::string_view name) const;
    Box3d box3(std::string_view name) const;
    glm::dmat4 transform(std::string_view name) const;
    /// The space `name`'s value is in: its declared space, or the one its spaceFrom choice
    /// picks (that read counts as a read of the choice).
    PropertySpace space(std::string_view name) const;
    /// False while the property's usedWhen condition does not hold.
    bool isUsed(std::string_view name) const;
    /// The declaration of `name` (its space, range); does not count as a read.
    const PropertyDecl &declaration(std::string_view name) const;
    const PropertyValue &value(std::string_view name) const;

    /// Declared names that no read has touched yet.
    std::vector<std::string> unreadNames() const;

private:
    const PropertyTable &m_table;
    const std::vector<PropertyValue> &m_values;
    mutable std::vector<bool> m_read;
};

} // namespace mvcl
