#pragma once
/// What every loader promises about a scene it returns; the tracer indexes without further
/// checks. The fuzz harnesses trap when a loaded scene breaks it.

#include <mvcl/model/Scene.h>

#include <cmath>

namespace mvcl::fuzz {

inline bool finite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline void checkSceneInvariants(const Scene &scene) {
    if (scene.materials.empty()) __builtin_trap();
    for (const TriangleMesh &mesh : scene.meshes) {
        if (mesh.material >= scene.materials.size()) __builtin_trap();
        if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) __builtin_trap();
        for (const glm::vec3 &p : mesh.positions)
            if (!finite(p)) __builtin_trap();
        for (const glm::uvec3 &t : mesh.indices)
            for (int k = 0; k < 3; ++k)
                if (t[k] >= mesh.positions.size()) __builtin_trap();
    }
}

} // namespace mvcl::fuzz
