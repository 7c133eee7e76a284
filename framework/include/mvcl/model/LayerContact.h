#pragma once
/// \file LayerContact.h
/// The contact tolerance of a layered scene: touching layers (organs sharing a wall, a part seated
/// in its housing) are often triangulated differently on each side, so the inner layer's facets
/// poke through the outer layer's by up to the facets' sagitta, far more than float rounding.
/// Within this distance along a ray, a hit on an outer layer (lower layer number) beats a nearer
/// hit on an inner layer. Off by default: without it the tracer still gives the outer layer
/// priority within the error bound of the intersection test, which is all that equal
/// tessellations need.

#include <mvcl/core/Export.h>

#include <mvcl/core/Bounds3.h>

#include <cstdint>
#include <string>

namespace mvcl {

struct MVCL_EXPORT LayerContact {
    enum class Measure : uint8_t {
        RelativeToSceneSize, ///< a fraction of the diagonal of the scene's bounds
        SceneUnits,          ///< a distance in scene (= world) units
    };
    /// 0 = off. Never negative or non-finite (parse() and the loaders refuse those).
    double distance = 0.0;
    Measure measure = Measure::RelativeToSceneSize;

    bool isEnabled() const { return distance > 0.0; }
    /// The distance in scene units for a scene with these bounds (0 when off or empty).
    float sceneUnits(const Bounds3f &sceneBounds) const;

    /// "1e-4" (relative to the scene's size) or "0.002units" (scene units; a space before
    /// "units" is allowed). Throws mvcl::Error("layer contact", problem) on anything else,
    /// negative or non-finite values included.
    static LayerContact parse(const std::string &text);
    /// The form parse() reads: "1e-04" or "0.002 units"; "0" when off.
    std::string toString() const;

    bool operator==(const LayerContact &other) const = default;
};

} // namespace mvcl
