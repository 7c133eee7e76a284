#pragma once
/// \file RenderSettings.h

#include <cstdint>

namespace mvcl {

struct RenderSettings {
    int width = 800;          ///< pixels, ≥ 1
    int height = 600;         ///< pixels, ≥ 1
    int samplesPerPixel = 4;  ///< stratified on a ⌈√n⌉×⌈√n⌉ grid, jittered; ≥ 1
    int threads = 0;          ///< 0 = all cores; the image does not depend on it
    int tileSize = 16;        ///< pixels per tile side
    uint32_t seed = 0;        ///< jitter seed; same seed → same image
};

} // namespace mvcl
