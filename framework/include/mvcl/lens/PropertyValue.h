#pragma once
/// \file PropertyValue.h
/// One typed value of a lens property. Every type has a canonical text form (toString) that
/// PropertyDecl::parse reads back, so files, the command line and round-trip tests share it.

#include <mvcl/core/Export.h>

#include <mvcl/lens/LensContext.h>
#include <mvcl/tracer/RayPolicy.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mvcl {

enum class PropertyType : uint8_t {
    Bool,       ///< text: true | false
    Int,        ///< text: decimal integer
    Real,       ///< text: decimal number (stored as double)
    Color,      ///< linear RGB; text: "r,g,b" (or "[r,g,b]")
    Choice,     ///< one of the declared choices; text: the choice
    LayerSet,   ///< layer mask; text: "all" | "none" | "0,2,5-7" | "2-" (layer 2 inward)
    RayTypeSet, ///< ray-type mask; text: "all" | "none" | "primary,shadow,reflection,refraction"
    Point3,     ///< a position in the declared space; text: "x,y,z" (or "[x,y,z]")
    Vector3,    ///< a direction or offset in the declared space; text: "x,y,z"
    Box3,       ///< axis-aligned box in the declared space; text: "minX,minY,minZ,maxX,maxY,maxZ"
    Transform,  ///< affine map in the declared space; text: "identity" or the 12 numbers of the
                ///< rows of [R | t] ("r00,r01,r02,t0,r10,r11,r12,t1,r20,r21,r22,t2")
};

MVCL_EXPORT const char *propertyTypeName(PropertyType type);

class MVCL_EXPORT PropertyValue {
public:
    PropertyValue() = default; ///< Bool false

    static PropertyValue boolean(bool value);
    static PropertyValue integer(int value);
    static PropertyValue real(double value);
    static PropertyValue color(const glm::vec3 &value);
    static PropertyValue choice(std::string value);
    static PropertyValue layerSet(uint32_t mask);
    static PropertyValue rayTypeSet(uint8_t mask);
    static PropertyValue point3(const glm::dvec3 &value);
    static PropertyValue vector3(const glm::dvec3 &value);
    static PropertyValue box3(const Box3d &value);
    /// Affine: the last row is taken as 0,0,0,1.
    static PropertyValue transform(const glm::dmat4 &value);

    PropertyType type() const { return m_type; }

    /// Typed access; each throws mvcl::Error if the value holds another type.
    bool toBool() const;
    int toInt() const;
    double toReal() const;
    glm::vec3 toColor() const;
    const std::string &toChoice() const;
    uint32_t toLayerSet() const;
    uint8_t toRayTypeSet() const;
    glm::dvec3 toPoint3() const;
    glm::dvec3 toVector3() const;
    Box3d toBox3() const;
    glm::dmat4 toTransform() const;
    /// The numbers of a Color, Point3, Vector3, Box3 or Transform in text order (3, 3, 3, 6
    /// or 12 of them), for range checks and editors; empty for the other types.
    std::vector<double> components() const;

    /// Canonical text form; PropertyDecl::parse(toString()) gives back an equal value.
    std::string toString() const;

    bool operator==(const PropertyValue &other) const = default;

private:
    explicit PropertyValue(PropertyType type) : m_type(type) {}

    PropertyType m_type = PropertyType::Bool;
    double m_number = 0.0;   // Bool, Int, Real
    std::array<double, 12> m_numbers{}; // Color, Point3, Vector3, Box3, Transform (text order)
    std::string m_text;      // Choice
    uint32_t m_bits = 0;     // LayerSet, RayTypeSet
};

/// Text helpers shared by the parser and by tools that print masks.
MVCL_EXPORT std::string layerSetToString(uint32_t mask);
/// Throws mvcl::Error("", problem) on malformed text.
MVCL_EXPORT uint32_t parseLayerSet(const std::string &text);
MVCL_EXPORT std::string rayTypeSetToString(uint8_t mask);
MVCL_EXPORT uint8_t parseRayTypeSet(const std::string &text);

} // namespace mvcl
