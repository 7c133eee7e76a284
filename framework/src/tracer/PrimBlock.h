#pragma once
// Private: leaf primitives in blocks of four, structure-of-arrays, so that the watertight test
// runs on four triangles at once (WatertightTriangle4.h) and a leaf is one or a few cache-line
// aligned loads instead of a walk over 48-byte records.

#include "KernelIsa.h"

#include <glm/vec3.hpp>

#include <cstdint>

namespace mvcl::detail {

/// 160 bytes. Lanes of a leaf are packed from lane 0; unused lanes of the last block are empty.
struct alignas(32) PrimBlock {
    /// [vertex][axis][lane]. A sphere lane keeps its centre in v[0] and its radius in v[1][0].
    float v[3][3][4];
    /// 1 << layer for triangle lanes; 0 for sphere and empty lanes, so the layer test of the
    /// 4-wide triangle kernel also leaves them out.
    uint32_t triangleLayerBit[4];

    MVCL_KERNEL_INLINE glm::vec3 vertex(int lane, int k) const { return {v[k][0][lane], v[k][1][lane], v[k][2][lane]}; }
    void setVertex(int lane, int k, const glm::vec3 &p) {
        for (int axis = 0; axis < 3; ++axis) v[k][axis][lane] = p[axis];
    }
};
static_assert(sizeof(PrimBlock) == 160);

/// Identity of one block lane (index 4 · block + lane), read only for hits and for spheres.
struct PrimInfo {
    uint32_t geometry = 0;
    uint32_t primitive = 0;
    uint8_t kind = 0; ///< PrimKind
    uint8_t layer = 0;
    uint16_t pad = 0;
};
static_assert(sizeof(PrimInfo) == 12);

} // namespace mvcl::detail
