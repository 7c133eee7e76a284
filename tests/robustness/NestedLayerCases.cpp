#include "NestedLayerCases.h"

#include "RobustnessCases.h"
#include "tracer/TracerTestUtil.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/tracer/RayOffset.h>
#include <mvcl/tracer/Tracer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace mvcl::robustness {

namespace {

constexpr int kOuterRings = 48, kOuterSegments = 96;
constexpr int kInnerRings = 64, kInnerSegments = 128;

bool isFinite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// Snell refraction of unit d at unit normal n (n against d), eta = n_from / n_to.
bool refract(const glm::vec3 &d, const glm::vec3 &n, float eta, glm::vec3 &t) {
    const float cosI = -glm::dot(n, d);
    const float k = 1.f - eta * eta * (1.f - cosI * cosI);
    if (k < 0.f) return false;
    t = glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n);
    return true;
}

/// A sphere of radius `radius` as a loader sees it: float positions in the mesh's own space
/// (rounded once), placed at `translation` in double and re-centred on `centre` in double.
TriangleMesh placedSphere(double radius, int rings, int segments, const glm::dvec3 &translation,
                          const glm::dvec3 &centre) {
    TriangleMesh mesh = test::makeUvSphere(glm::dvec3(0.0), radius, rings, segments);
    for (glm::vec3 &p : mesh.positions) p = glm::vec3((translation + glm::dvec3(p)) - centre);
    return mesh;
}

} // namespace

std::vector<double> nestedLayerGaps() { return {0.0, 1e-7, 3e-7, 1e-6, 1e-5, 1e-4, 1e-3}; }

std::vector<double> nestedLayerScales() { return {1e-7, 1e-3, 1.0, 1e3, 1e7}; }

std::vector<double> nestedLayerTranslations() { return {0.0, 1e3, 1e7}; }

double nestedLayerDifferentTolerance() {
    // A facet of the outer sphere is half of a quad of π/rings × 2π/segments (square here); its
    // plane lies below the sphere by up to the sagitta of the quad's diagonal, 1 − cos(√2·π /
    // (2·rings)) of the radius. The scene's size is its bounds' diagonal, 2√3 radii.
    const double sagitta = 1.0 - std::cos(std::numbers::sqrt2 * std::numbers::pi / (2.0 * kOuterRings));
    return 1.5 * sagitta / (2.0 * std::sqrt(3.0));
}

bool nestedRefractionRequired(const NestedLayerConfig &config) {
    const float k = float(config.scale);
    const double ulp = double(nextFloatUp(k)) - double(k);
    return config.tessellation == NestedTessellation::Equal && config.gap * config.scale >= 32.0 * ulp;
}

Scene makeNestedSpheres(const NestedLayerConfig &config) {
    // Translation in units of the model's size: the doubles keep 10⁷ sizes exactly enough.
    const glm::dvec3 translation(config.translation * config.scale);
    const double outerRadius = (1.0 + config.gap) * config.scale;
    // The loader re-centres on the world bounds' centre: the outer sphere's float extent.
    const glm::dvec3 centre = translation;
    const bool equal = config.tessellation == NestedTessellation::Equal;
    Scene scene;
    scene.name = "nested-spheres";
    Material outerMaterial, innerMaterial;
    outerMaterial.diffuse = outerMaterial.ambient = glm::vec3(0.8f, 0.8f, 0.8f);
    innerMaterial.diffuse = innerMaterial.ambient = glm::vec3(0.9f, 0.1f, 0.1f);
    scene.materials = {outerMaterial, innerMaterial};
    TriangleMesh outer = placedSphere(outerRadius, kOuterRings, kOuterSegments, translation, centre);
    outer.name = "outer";
    outer.layer = 0;
    outer.material = 0;
    TriangleMesh inner = placedSphere(config.scale, equal ? kOuterRings : kInnerRings,
                                      equal ? kOuterSegments : kInnerSegments, translation, centre);
    inner.name = "inner";
    inner.layer = 1;
    inner.material = 1;
    scene.meshes = {outer, inner};
    scene.layerContact.distance = config.contactTolerance;
    Light light;
    light.position = glm::vec3(config.scale * glm::dvec3(3.0, 4.0, 5.0));
    scene.lights.push_back(light);
    return scene;
}

/// A pinhole camera 5.25 radii from the centre, 40° vertical field of view, computed here in
/// double (not by mvcl::Camera, which the flag-invariance builds compile with FMA contraction):
/// the rays must be the same in every build the digest compares.
struct PinholeRays {
    glm::dvec3 eye, forward, right, up;
    double tanHalfFov;
    PinholeRays(double radius) {
        const glm::dvec3 toEye = glm::normalize(glm::dvec3(1.0, 0.7, 1.6));
        eye = 5.25 * radius * toEye;
        forward = -toEye;
        right = glm::normalize(glm::cross(forward, glm::dvec3(0.0, 1.0, 0.0)));
        up = glm::cross(right, forward);
        tanHalfFov = std::tan(20.0 * std::numbers::pi / 180.0);
    }
    Ray at(int x, int y, int width, int height) const {
        const double u = (2.0 * (double(x) + 0.5) / double(width) - 1.0) * tanHalfFov * double(width) / double(height);
        const double v = (1.0 - 2.0 * (double(y) + 0.5) / double(height)) * tanHalfFov;
        return {glm::vec3(eye), glm::vec3(glm::normalize(forward + u * right + v * up))};
    }
};

NestedLayerCounts runNestedLayerCell(const NestedLayerConfig &config, int threads) {
    const Scene scene = makeNestedSpheres(config);
    const Tracer tracer(scene);
    const PinholeRays camera((1.0 + config.gap) * config.scale);
    const glm::vec3 light = scene.lights.front().position;
    const bool refractionRequired = nestedRefractionRequired(config);
    std::vector<NestedLayerCounts> rows(std::size_t(config.height));
    parallelFor(rows.size(), std::max(1, threads), [&](std::size_t y) {
        NestedLayerCounts &c = rows[y];
        uint64_t query = uint64_t(y) * uint64_t(config.width) * 4u;
        auto trace = [&](const Ray &ray, const RayQuery &q, Hit &hit) {
            const bool found = tracer.closestHit(ray, q, hit);
            c.hash += hitHash(query++, found, hit);
            if (found && (!std::isfinite(hit.t) || !isFinite(ray.at(hit.t)))) ++c.nonFinite;
            return found;
        };
        for (int x = 0; x < config.width; ++x) {
            const Ray primary = camera.at(x, y, config.width, config.height);
            Hit hit;
            if (!trace(primary, {}, hit)) continue;
            ++c.modelPixels;
            if (hit.layer != 0) {
                ++c.innerShowing;
                continue;
            }
            const SurfaceInteraction si = tracer.interaction(primary, hit);
            glm::vec3 n = si.geometricNormal;
            if (glm::dot(n, primary.direction) > 0.f) n = -n;
            const glm::vec3 toLight = light - si.position;
            const float distance = glm::length(toLight);
            const glm::vec3 l = toLight / distance;
            if (glm::dot(n, l) > 0.05f) {
                const Ray shadow{offsetRayOrigin(si.position, si.positionError, n, l), l};
                RayQuery q;
                q.tMax = distance;
                Hit blocker;
                const bool blocked = tracer.anyHit(shadow, q);
                if (blocked || trace(shadow, q, blocker)) ++c.shadowAcne;
            }
            const glm::vec3 r = primary.direction - 2.f * glm::dot(n, primary.direction) * n;
            Hit next;
            if (trace({offsetRayOrigin(si.position, si.positionError, n, r), r}, {}, next)) ++c.reflectionAcne;
            glm::vec3 refracted;
            if (refractionRequired && refract(primary.direction, n, 1.f / 1.5f, refracted)) {
                const Ray ray{offsetRayOrigin(si.position, si.positionError, n, refracted), refracted};
                if (!trace(ray, {}, next) || next.layer != 1) ++c.refractionNotInner;
            }
        }
    });
    NestedLayerCounts total;
    for (const NestedLayerCounts &c : rows) {
        total.modelPixels += c.modelPixels;
        total.innerShowing += c.innerShowing;
        total.shadowAcne += c.shadowAcne;
        total.reflectionAcne += c.reflectionAcne;
        total.refractionNotInner += c.refractionNotInner;
        total.nonFinite += c.nonFinite;
        total.hash += c.hash;
    }
    return total;
}

std::string describe(const NestedLayerConfig &config) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "g=%.0e k=%.0e T=%.0e·k %s tol=%.2e %dx%d", config.gap, config.scale,
                  config.translation, config.tessellation == NestedTessellation::Equal ? "equal" : "different",
                  config.contactTolerance, config.width, config.height);
    return buf;
}

} // namespace mvcl::robustness
