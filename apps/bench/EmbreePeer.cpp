#include "EmbreePeer.h"

#ifdef MVCL_HAVE_EMBREE

#include <limits>

namespace mvcl::bench {

std::atomic<long long> g_embreeBytes{0};
std::atomic<long long> g_embreePeak{0};

bool embreeMemoryMonitor(void *, ssize_t bytes, bool) {
    const long long now = g_embreeBytes.fetch_add(bytes) + bytes;
    long long peak = g_embreePeak.load();
    while (now > peak && !g_embreePeak.compare_exchange_weak(peak, now)) {
    }
    return true;
}

RTCScene buildEmbree(RTCDevice device, const Scene &scene, RTCBuildQuality quality) {
    RTCScene es = rtcNewScene(device);
    rtcSetSceneBuildQuality(es, quality);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const TriangleMesh &mesh = scene.meshes[m];
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        // Copied into Embree-owned buffers: Embree needs 16 bytes of padding after the last
        // vertex, which a std::vector<vec3> does not guarantee.
        auto *v = static_cast<float *>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
            mesh.positions.size()));
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            v[3 * i] = mesh.positions[i].x;
            v[3 * i + 1] = mesh.positions[i].y;
            v[3 * i + 2] = mesh.positions[i].z;
        }
        auto *idx = static_cast<unsigned *>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
            mesh.indices.size()));
        for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
            idx[3 * i] = mesh.indices[i].x;
            idx[3 * i + 1] = mesh.indices[i].y;
            idx[3 * i + 2] = mesh.indices[i].z;
        }
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(es, g, unsigned(m));
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(es);
    return es;
}

void intersectEmbree(RTCScene scene, const Ray &r, RTCRayHit &rh) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = 0.f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = ~0u;
    rh.ray.flags = 0;
    rh.ray.time = 0.f;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
}

} // namespace mvcl::bench

#endif
