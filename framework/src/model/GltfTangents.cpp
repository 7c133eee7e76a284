#include "GltfTangents_p.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace mvcl::gltf {

std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3> &positions,
                                        const std::vector<glm::vec3> &normals, const std::vector<glm::vec2> &uvs,
                                        const std::vector<glm::uvec3> &triangles) {
    const std::size_t n = positions.size();
    std::vector<glm::dvec3> tan(n, glm::dvec3(0.0)), bitan(n, glm::dvec3(0.0)), faceNormal(n, glm::dvec3(0.0));
    for (const glm::uvec3 &t : triangles) {
        const glm::dvec3 p0(positions[t.x]), p1(positions[t.y]), p2(positions[t.z]);
        const glm::dvec2 w0(uvs[t.x]), w1(uvs[t.y]), w2(uvs[t.z]);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
        const glm::dvec2 d1 = w1 - w0, d2 = w2 - w0;
        const glm::dvec3 fn = glm::cross(e1, e2);
        for (int k = 0; k < 3; ++k) faceNormal[t[k]] += fn;
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 0.0) || !std::isfinite(det)) continue;
        const double r = 1.0 / det;
        const glm::dvec3 sdir = (e1 * d2.y - e2 * d1.y) * r; // ∂p/∂u
        const glm::dvec3 tdir = (e2 * d1.x - e1 * d2.x) * r; // ∂p/∂v
        for (int k = 0; k < 3; ++k) {
            tan[t[k]] += sdir;
            bitan[t[k]] += tdir;
        }
    }
    std::vector<glm::vec4> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 nrm = normals.size() == n ? glm::dvec3(normals[i]) : faceNormal[i];
        const double nl = glm::length(nrm);
        nrm = nl > 0.0 ? nrm / nl : glm::dvec3(0.0, 0.0, 1.0);
        glm::dvec3 t = tan[i] - glm::dot(tan[i], nrm) * nrm;
        double len = glm::length(t);
        if (!(len > 1e-20) || !std::isfinite(len)) {
            // Any perpendicular: the axis least aligned with the normal, projected.
            const glm::dvec3 axis = std::abs(nrm.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
            t = axis - glm::dot(axis, nrm) * nrm;
            len = glm::length(t);
        }
        t /= len;
        // glTF: bitangent = w · (normal × tangent); w = −1 where the uv map is mirrored.
        const double w = glm::dot(glm::cross(nrm, t), bitan[i]) < 0.0 ? -1.0 : 1.0;
        out[i] = glm::vec4(float(t.x), float(t.y), float(t.z), float(w));
    }
    return out;
}

} // namespace mvcl::gltf
