#pragma once
/// \file PropertyInterpolation.h
/// Values between two keyframes of a lens property, by the property's declared type: reals,
/// integers, points, vectors and boxes interpolate component by component; colours too, and
/// since property colours are linear RGB that is interpolation in linear light (an sRGB blend
/// would darken the middle); choices, booleans, layer and ray-type sets and transforms step
/// (the earlier keyframe's value holds until the later one's time). Results stay in the
/// declared range.

#include <mvcl/core/Export.h>

#include <mvcl/lens/PropertyDecl.h>

#include <cstdint>
#include <optional>
#include <string_view>

namespace mvcl {

/// How the fraction of the way between two keyframes advances with time.
enum class Easing : uint8_t {
    Linear,     ///< s
    SmoothStep, ///< 3s² − 2s³: starts and stops without a jump in speed
};

/// "linear", "smooth".
MVCL_EXPORT const char *easingName(Easing easing);
/// The easing named `name`, or none.
MVCL_EXPORT std::optional<Easing> easingNamed(std::string_view name);

/// `fraction` (clamped to [0, 1]) as `easing` shapes it.
MVCL_EXPORT double eased(Easing easing, double fraction);

/// Whether values of `type` change gradually between keyframes (else they step).
MVCL_EXPORT bool interpolatesContinuously(PropertyType type);

/// The value a fraction `s` (0 = `from`, 1 = `to`, already eased) of the way between two values
/// of `decl`. Continuous types: from + (to − from)·s per component, integers rounded to the
/// nearest, clamped to the declared range; step types: `from` until s reaches 1. Throws
/// mvcl::Error(decl.name, problem) when a value is not of the declared type.
MVCL_EXPORT PropertyValue interpolateProperty(const PropertyDecl &decl, const PropertyValue &from,
                                              const PropertyValue &to, double s);

} // namespace mvcl
