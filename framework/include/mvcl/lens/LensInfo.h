#pragma once
/// \file LensInfo.h
/// What a lens type is: its name, a description, its parameter table, the ray types it acts on
/// by default, its declared algebra and whether it follows the view. One static LensInfo per plugin.

#include <mvcl/lens/PropertyDecl.h>
#include <mvcl/tracer/RayPolicy.h>

#include <cstdint>
#include <string>

namespace mvcl {

/// Claims the conformance suite checks by rendering permutations.
struct LensAlgebra {
    /// Swapping this lens with any neighbour that also declares `commutes` leaves every pixel
    /// unchanged, whatever both lenses' properties are.
    bool commutes = false;
    /// Stacking this lens twice with the same properties equals stacking it once.
    bool idempotent = false;
};

struct LensInfo {
    std::string name;         ///< type name in files and on the command line, e.g. "layer"
    std::string description;  ///< one sentence
    PropertyTable properties; ///< the lens's own parameters ("rays" is added by Lens)
    uint8_t defaultRayTypes = kAllRayTypes; ///< default of the common "rays" property
    LensAlgebra algebra;
    /// contribute() reads the camera or the image size of its LensContext (or takes properties
    /// in view space): the lens is re-contributed whenever the view changes. The conformance
    /// suite checks that a lens without it contributes the same under any view.
    bool dependsOnView = false;
};

} // namespace mvcl
