#pragma once
// Private: the per-ray constants of packet traversal (PacketTraversal.inl) in ray lanes, one array
// per quantity, so that the 16 rays of a packet load as one AVX-512 or two AVX2 registers.

#include <mvcl/tracer/Tracer.h>

namespace mvcl::detail {

inline constexpr int kPacketLanes = Tracer::kPacketSize;

struct alignas(64) PacketRays {
    float ox[kPacketLanes], oy[kPacketLanes], oz[kPacketLanes]; ///< origin
    float dx[kPacketLanes], dy[kPacketLanes], dz[kPacketLanes]; ///< direction
    float tHigh[kPacketLanes]; ///< box culling bound of each ray
    float tCap[kPacketLanes];  ///< triangle kernel cap of each ray: min(tMax, best hit's cap)
};

} // namespace mvcl::detail
