#include "TracerPrivate.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/model/Scene.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>

// Tracer::interaction on its own: it reads the scene, not the BVH.

namespace mvcl {

SurfaceInteraction Tracer::interaction(const Ray &ray, const Hit &hit) const {
    SurfaceInteraction si;
    // d->scene, not scene(): that is a call into Tracer.cpp, once per shaded point.
    const Scene &scene = d->scene;
    switch (hit.kind) {
    case GeometryKind::Triangle: {
        const TriangleMesh &mesh = scene.meshes[hit.geometry];
        const glm::uvec3 tri = mesh.indices[hit.primitive];
        const glm::vec3 &p0 = mesh.positions[tri.x];
        const glm::vec3 &p1 = mesh.positions[tri.y];
        const glm::vec3 &p2 = mesh.positions[tri.z];
        const float b1 = hit.u, b2 = hit.v, b0 = 1.f - b1 - b2;
        // From barycentrics, not o + t·d: the error then scales with the vertices, not with the
        // distance travelled (pbrt-v4 §6.8.5).
        // Each product rounded on its own (unfused): hit points must not depend on FMA contraction.
        const auto unfusedProduct = [](float b, const glm::vec3 &p) {
            return glm::vec3(mulUnfused(b, p.x), mulUnfused(b, p.y), mulUnfused(b, p.z));
        };
        const glm::vec3 q0 = unfusedProduct(b0, p0), q1 = unfusedProduct(b1, p1), q2 = unfusedProduct(b2, p2);
        si.position = q0 + q1 + q2;
        si.positionError = gamma(7) * (glm::abs(q0) + glm::abs(q1) + glm::abs(q2));
        const glm::dvec3 e1 = glm::dvec3(p1) - glm::dvec3(p0);
        const glm::dvec3 e2 = glm::dvec3(p2) - glm::dvec3(p0);
        si.geometricNormal = glm::vec3(glm::normalize(glm::cross(e1, e2)));
        si.shadingNormal = si.geometricNormal;
        if (mesh.normals.size() == mesh.positions.size()) {
            const glm::vec3 ns =
                b0 * mesh.normals[tri.x] + b1 * mesh.normals[tri.y] + b2 * mesh.normals[tri.z];
            const float len = glm::length(ns);
            if (len > 0.f && std::isfinite(len)) {
                si.shadingNormal = ns / len;
                if (glm::dot(si.shadingNormal, si.geometricNormal) < 0.f)
                    si.shadingNormal = -si.shadingNormal;
            }
        }
        si.material = mesh.material;
        si.layer = mesh.layer;
        break;
    }
    case GeometryKind::Sphere: {
        const Sphere &s = scene.spheres[hit.geometry];
        // Reproject onto the sphere in double: the point is then exact up to the final rounding.
        glm::dvec3 pObj = glm::dvec3(ray.origin) - glm::dvec3(s.center) +
                          double(hit.t) * glm::dvec3(ray.direction);
        pObj *= double(s.radius) / glm::length(pObj);
        si.position = glm::vec3(glm::dvec3(s.center) + pObj);
        si.positionError =
            gamma(5) * glm::abs(glm::vec3(pObj)) + gamma(2) * glm::abs(si.position);
        si.geometricNormal = glm::vec3(glm::normalize(pObj));
        si.shadingNormal = si.geometricNormal;
        si.material = s.material;
        si.layer = s.layer;
        break;
    }
    case GeometryKind::Plane: {
        const Plane &pl = scene.planes[hit.geometry];
        const Private::PlaneFrame &frame = d->planeFrames[hit.geometry];
        const glm::dvec3 &n = frame.unitNormal;
        // o + t·d in double, then projected onto the plane along its normal: the residual error
        // is the float rounding of t (along the ray) and of the result.
        glm::dvec3 p = glm::dvec3(ray.origin) + double(hit.t) * glm::dvec3(ray.direction);
        p -= (glm::dot(n, p) - frame.offset) * n;
        si.position = glm::vec3(p);
        const glm::vec3 td = hit.t * ray.direction;
        si.positionError = gamma(3) * (glm::abs(si.position) + glm::abs(td));
        si.geometricNormal = glm::vec3(n);
        si.shadingNormal = si.geometricNormal;
        si.material = pl.material;
        si.layer = pl.layer;
        break;
    }
    }
    return si;
}

} // namespace mvcl
