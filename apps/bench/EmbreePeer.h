#pragma once
/// \file EmbreePeer.h
/// Intel Embree 3 as the peer tracer of mvcl-bench: the same triangles in an Embree scene, and
/// its single-ray closest-hit query on our rays. Only with MVCL_HAVE_EMBREE (libembree-dev).

#ifdef MVCL_HAVE_EMBREE

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Ray.h>

#include <embree3/rtcore.h>

#include <atomic>

namespace mvcl::bench {

/// Bytes Embree holds now and at most, counted by embreeMemoryMonitor.
extern std::atomic<long long> g_embreeBytes;
extern std::atomic<long long> g_embreePeak;
/// For rtcSetDeviceMemoryMonitorFunction: counts Embree's allocations into g_embree*.
bool embreeMemoryMonitor(void *, ssize_t bytes, bool);

/// The scene's triangle meshes (geometry ID = mesh index), committed. Medium quality is Embree's
/// binned SAH build, the peer of ours; low is its Morton build, the peer of BvhQuality::Quick.
RTCScene buildEmbree(RTCDevice device, const Scene &scene, RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM);

/// rtcIntersect1 over [0, ∞), the query closestHit answers with a default RayQuery.
void intersectEmbree(RTCScene scene, const Ray &ray, RTCRayHit &rayHit);

} // namespace mvcl::bench

#endif
