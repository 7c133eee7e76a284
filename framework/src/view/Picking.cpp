#include <mvcl/view/Picking.h>

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>

#include <glm/geometric.hpp>

namespace mvcl {

namespace {

/// Names and material of the hit geometry, by kind.
void describeGeometry(const Scene &scene, const Hit &hit, PickResult &result) {
    switch (hit.kind) {
    case GeometryKind::Triangle: {
        const TriangleMesh &mesh = scene.meshes[hit.geometry];
        result.objectName = mesh.name;
        result.meshName = mesh.meshName;
        result.nodeName = mesh.nodeName;
        result.sourceNode = mesh.sourceNode;
        result.sourceMesh = mesh.sourceMesh;
        break;
    }
    case GeometryKind::Sphere: result.objectName = scene.spheres[hit.geometry].name; break;
    case GeometryKind::Plane: result.objectName = scene.planes[hit.geometry].name; break;
    }
}

} // namespace

Ray pixelCentreRay(const Camera &camera, const PixelPolicy &policy, int x, int y, int width, int height) {
    const glm::vec2 sample = policy.samplePosition({float(x) + 0.5f, float(y) + 0.5f}, width, height);
    return camera.generateRay(sample.x, sample.y, width, height);
}

PickResult pick(const Tracer &tracer, const Camera &camera, const PolicyMap &map, int x, int y) {
    PickResult result;
    if (x < 0 || y < 0 || x >= map.width() || y >= map.height()) return result;

    result.policy = map.dominantPolicyIndex(x, y);
    const PixelPolicy &policy = map.policy(result.policy);
    result.lensSet = policy.lensSet;
    result.samplePosition = policy.samplePosition({float(x) + 0.5f, float(y) + 0.5f}, map.width(), map.height());
    result.ray = pixelCentreRay(camera, policy, x, y, map.width(), map.height());

    // The integrator's primary query: the pick sees exactly what the pixel's first sample sees.
    Hit hit;
    if (!tracer.closestHit(result.ray, policy.ray.query(RayType::Primary), hit)) return result;

    const Scene &scene = tracer.scene();
    const SurfaceInteraction si = tracer.interaction(result.ray, hit);
    result.hit = true;
    result.distance = hit.t;
    result.kind = hit.kind;
    result.geometry = hit.geometry;
    result.primitive = hit.primitive;
    result.layer = si.layer;
    if (const Layer *layer = scene.layers.find(si.layer)) result.layerName = layer->name;
    describeGeometry(scene, hit, result);
    result.material = si.material;
    if (si.material < scene.materials.size()) result.materialName = scene.materials[si.material].name;
    result.scenePosition = si.position;
    result.worldPosition = glm::dvec3(si.position) + scene.worldOrigin;
    result.shadingNormal = si.shadingNormal;
    result.geometricNormal = si.geometricNormal;
    result.frontFacing = glm::dot(si.geometricNormal, result.ray.direction) < 0.f;
    return result;
}

} // namespace mvcl
