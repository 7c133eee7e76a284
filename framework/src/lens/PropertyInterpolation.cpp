#include <mvcl/lens/PropertyInterpolation.h>

#include <mvcl/core/Error.h>

#include <algorithm>
#include <cmath>

namespace mvcl {

namespace {

double lerp(double from, double to, double s) { return from + (to - from) * s; }

double clamped(double value, const PropertyDecl &decl) { return std::clamp(value, decl.minimum, decl.maximum); }

} // namespace

const char *easingName(Easing easing) {
    switch (easing) {
    case Easing::Linear: return "linear";
    case Easing::SmoothStep: return "smooth";
    }
    return "linear";
}

std::optional<Easing> easingNamed(std::string_view name) {
    if (name == "linear") return Easing::Linear;
    if (name == "smooth") return Easing::SmoothStep;
    return std::nullopt;
}

double eased(Easing easing, double fraction) {
    const double s = std::clamp(fraction, 0.0, 1.0);
    return easing == Easing::SmoothStep ? s * s * (3.0 - 2.0 * s) : s;
}

bool interpolatesContinuously(PropertyType type) {
    switch (type) {
    case PropertyType::Int:
    case PropertyType::Real:
    case PropertyType::Color:
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3: return true;
    // A blend of two affine maps need not be invertible; sets and choices have no "between".
    case PropertyType::Bool:
    case PropertyType::Choice:
    case PropertyType::LayerSet:
    case PropertyType::RayTypeSet:
    case PropertyType::Transform: return false;
    }
    return false;
}

PropertyValue interpolateProperty(const PropertyDecl &decl, const PropertyValue &from, const PropertyValue &to,
                                  double s) {
    if (from.type() != decl.type || to.type() != decl.type)
        throw Error(decl.name, std::string("expected values of type ") + propertyTypeName(decl.type));
    if (!interpolatesContinuously(decl.type)) return s >= 1.0 ? to : from;
    // The ends themselves, exactly: a keyframe's value must render as written.
    if (s <= 0.0) return from;
    if (s >= 1.0) return to;
    switch (decl.type) {
    case PropertyType::Int:
        return PropertyValue::integer(int(std::lround(clamped(lerp(from.toInt(), to.toInt(), s), decl))));
    case PropertyType::Real: return PropertyValue::real(clamped(lerp(from.toReal(), to.toReal(), s), decl));
    default: break;
    }
    const std::vector<double> a = from.components(), b = to.components();
    std::vector<double> c(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) c[i] = clamped(lerp(a[i], b[i], s), decl);
    switch (decl.type) {
    case PropertyType::Color: return PropertyValue::color(glm::vec3(float(c[0]), float(c[1]), float(c[2])));
    case PropertyType::Point3: return PropertyValue::point3({c[0], c[1], c[2]});
    case PropertyType::Vector3: return PropertyValue::vector3({c[0], c[1], c[2]});
    case PropertyType::Box3: return PropertyValue::box3({{c[0], c[1], c[2]}, {c[3], c[4], c[5]}});
    default: return from;
    }
}

} // namespace mvcl
