#pragma once
/// \file PropertyDecl.h
/// A lens parameter declared once — name, type, default, range, unit, doc — and used for lens
/// files, the command line, generated UI, the docs and the conformance tests (Mitsuba/OSPRay
/// style). A plugin lists its declarations in a PropertyTable at the top of its one source file.

#include <mvcl/core/Export.h>

#include <mvcl/lens/PropertyValue.h>

#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mvcl {

struct MVCL_EXPORT PropertyDecl {
    std::string name;  ///< lowerCamelCase key used in files and on the command line
    PropertyType type = PropertyType::Bool;
    PropertyValue defaultValue;
    /// Int, Real; per component for Color, Point3, Vector3 and Box3 (not Transform).
    double minimum = -std::numeric_limits<double>::infinity();
    double maximum = std::numeric_limits<double>::infinity();
    /// Point3, Vector3, Box3, Transform: the space the value is given in (LensContext converts).
    PropertySpace space = PropertySpace::World;
    std::string unit;  ///< e.g. "scene units", "px"; empty if unitless
    std::string doc;   ///< one sentence for docs, tooltips and --help
    std::vector<std::string> choices; ///< Choice only

    /// Point3, Vector3, Box3, Transform whose space a Choice property of the same lens picks
    /// (clip's frame=scene|world): the choice's name and the space of each of its values.
    /// Empty: `space` always. PropertyValues::space() resolves it, so that editors (gizmos)
    /// and the lens agree on where the value sits.
    struct SpaceChoice {
        std::string property;
        std::vector<std::pair<std::string, PropertySpace>> spaces;
        bool operator==(const SpaceChoice &) const = default;
    };
    SpaceChoice spaceFrom;
    /// The property matters only while the Choice property `usedWhen.property` has the value
    /// `usedWhen.value` (clip's sphere centre only while volume=sphere). Empty: always.
    /// Editors hide or dim it otherwise; gizmos are offered only for properties in use.
    struct Condition {
        std::string property;
        std::string value;
        bool operator==(const Condition &) const = default;
    };
    Condition usedWhen;

    /// This declaration with its space picked by the Choice property `choice` (see spaceFrom).
    PropertyDecl withSpaceFrom(std::string choice, std::vector<std::pair<std::string, PropertySpace>> spaces) const;
    /// This declaration used only while `choice` has `value` (see usedWhen).
    PropertyDecl whenChoice(std::string choice, std::string value) const;

    static PropertyDecl boolean(std::string name, bool defaultValue, std::string doc);
    static PropertyDecl integer(std::string name, int defaultValue, int minimum, int maximum,
                                std::string unit, std::string doc);
    static PropertyDecl real(std::string name, double defaultValue, double minimum,
                             double maximum, std::string unit, std::string doc);
    /// Components range over [0, ∞) unless narrowed.
    static PropertyDecl color(std::string name, const glm::vec3 &defaultValue, std::string doc);
    static PropertyDecl choice(std::string name, std::string defaultValue,
                               std::vector<std::string> choices, std::string doc);
    static PropertyDecl layers(std::string name, uint32_t defaultMask, std::string doc);
    static PropertyDecl rayTypes(std::string name, uint8_t defaultMask, std::string doc);
    /// Components range over (−∞, ∞) unless narrowed.
    static PropertyDecl point3(std::string name, const glm::dvec3 &defaultValue, PropertySpace space,
                               std::string unit, std::string doc);
    static PropertyDecl vector3(std::string name, const glm::dvec3 &defaultValue, PropertySpace space,
                                std::string unit, std::string doc);
    /// A box's minimum must not exceed its maximum on any axis.
    static PropertyDecl box3(std::string name, const Box3d &defaultValue, PropertySpace space,
                             std::string unit, std::string doc);
    /// Finite, with an invertible linear part.
    static PropertyDecl transform(std::string name, const glm::dmat4 &defaultValue, PropertySpace space,
                                  std::string doc);

    /// Parses `text` into a value of this type and checks it; throws mvcl::Error(name, problem).
    PropertyValue parse(std::string_view text) const;
    /// Checks type, finiteness, range and choices; throws mvcl::Error(name, problem).
    void validate(const PropertyValue &value) const;
    /// "[min, max] unit" / "one of a|b|c" — for docs and --help.
    std::string rangeText() const;
    /// "world space", or "space by frame (scene: bounds, world: world)".
    std::string spaceText() const;
};

using PropertyTable = std::vector<PropertyDecl>;

/// The declaration named `name` in `table`, or nullptr.
MVCL_EXPORT const PropertyDecl *findProperty(const PropertyTable &table, std::string_view name);

} // namespace mvcl
