#include <mvcl/model/Scene.h>

namespace mvcl {

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const TriangleMesh &m : meshes) n += m.indices.size();
    return n;
}

Bounds3f Scene::bounds() const {
    Bounds3f b;
    for (const TriangleMesh &m : meshes)
        for (const glm::uvec3 &tri : m.indices)
            for (int k = 0; k < 3; ++k) b.expand(m.positions[tri[k]]);
    for (const Sphere &s : spheres) {
        b.expand(s.center - glm::vec3(s.radius));
        b.expand(s.center + glm::vec3(s.radius));
    }
    return b;
}

} // namespace mvcl
