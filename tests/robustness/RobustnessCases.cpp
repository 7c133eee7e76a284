#include "RobustnessCases.h"

#include "tracer/TracerTestUtil.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/core/WorkerPool.h>
#include <mvcl/tracer/RayOffset.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

namespace mvcl::robustness {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

bool isFinite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// Runs body(begin, end, counts) for consecutive slices of [0, n) of `slice` items each, on
/// `threads` threads of the worker pool, and sums the counts; the sums (and the order-independent
/// hash) depend neither on the slicing nor on the thread count.
template <class Body>
CaseCounts parallelCounts(uint64_t n, int threads, uint64_t slice, const Body &body) {
    const uint64_t slices = (n + slice - 1) / slice;
    std::vector<CaseCounts> partial(static_cast<std::size_t>(slices));
    parallelFor(static_cast<std::size_t>(slices), std::max(1, threads), [&](std::size_t k) {
        body(uint64_t(k) * slice, std::min(n, uint64_t(k + 1) * slice), partial[k]);
    });
    CaseCounts total;
    for (const CaseCounts &c : partial) {
        total.rays += c.rays;
        total.failures += c.failures;
        total.duplicates += c.duplicates;
        total.hash += c.hash;
    }
    return total;
}

/// |a − b| in units in the last place (same sign assumed; t values are positive).
uint32_t ulpDistance(float a, float b) {
    const uint32_t ia = std::bit_cast<uint32_t>(a), ib = std::bit_cast<uint32_t>(b);
    return ia > ib ? ia - ib : ib - ia;
}

/// Snell refraction of unit d at unit normal n (n against d), eta = n_from / n_to. Returns false
/// on total internal reflection.
bool refract(const glm::vec3 &d, const glm::vec3 &n, float eta, glm::vec3 &t) {
    const float cosI = -glm::dot(n, d);
    const float k = 1.f - eta * eta * (1.f - cosI * cosI);
    if (k < 0.f) return false;
    t = glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n);
    return true;
}

} // namespace

// ---------------------------------------------------------------------------------------------

CaseRng::CaseRng(uint64_t seed, uint64_t stream) : m_state(mix64(seed) ^ mix64(stream + 0x632be59bd9b4e019ull)) {}

uint64_t mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

uint64_t CaseRng::next() {
    m_state += 0x9e3779b97f4a7c15ull;
    uint64_t z = m_state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double CaseRng::uniform() { return double(next() >> 11) * 0x1.0p-53; }

glm::dvec3 CaseRng::unitVector() {
    for (;;) {
        const glm::dvec3 v{uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0)}; // braces: left-to-right
        const double len2 = glm::dot(v, v);
        if (len2 > 1e-6 && len2 <= 1.0) return v / std::sqrt(len2);
    }
}

uint64_t hitHash(uint64_t rayIndex, bool found, const Hit &hit) {
    if (!found) return mix64(rayIndex * 0x2545f4914f6cdd1dull);
    const uint64_t key = (uint64_t(std::bit_cast<uint32_t>(hit.t)) << 32) ^
                         (uint64_t(hit.primitive) << 8) ^ (uint64_t(hit.geometry) << 40) ^
                         (uint64_t(hit.layer) << 2) ^ uint64_t(hit.kind);
    return mix64(mix64(rayIndex) ^ key);
}

// ---------------------------------------------------------------------------------------------
// Watertight spheres

TriangleMesh makeWatertightSphere(const WatertightConfig &config) {
    if (config.mesh == SphereMesh::Uv200) return test::makeUvSphere(config.center, 2.0, 200, 200);
    // The unit 16 × 16 sphere (valence 16 at the poles), each vertex pushed to its own radius in
    // [1, 6]: a closed, star-shaped, strongly non-convex mesh with long thin triangles.
    TriangleMesh mesh = test::makeUvSphere(glm::dvec3(0.0), 1.0, 16, 16);
    CaseRng rng(config.seed, 0xfeedull);
    for (glm::vec3 &p : mesh.positions) p = glm::vec3(config.center + glm::dvec3(p) * rng.uniform(1.0, 6.0));
    mesh.normals.clear();
    return mesh;
}

std::vector<WatertightConfig> standardWatertightConfigs(uint64_t rays) {
    const glm::dvec3 far(148376.0, 1234.0, -223423.0);
    std::vector<WatertightConfig> configs;
    uint64_t seed = 100;
    for (const auto &[where, center] : {std::pair{"Origin", glm::dvec3(0.0)}, std::pair{"Far", far}}) {
        const std::string at = where;
        configs.push_back({"Sphere200" + at + "RandomDirections", center, SphereMesh::Uv200,
                           SphereTargets::RandomDirections, rays, ++seed, false});
        configs.push_back({"Sphere200" + at + "Vertices", center, SphereMesh::Uv200,
                           SphereTargets::Vertices, rays, ++seed, false});
        configs.push_back({"Sphere200" + at + "EdgePoints", center, SphereMesh::Uv200,
                           SphereTargets::EdgePoints, rays, ++seed, false});
        configs.push_back({"Jittered16" + at + "Vertices", center, SphereMesh::JitteredValence16,
                           SphereTargets::Vertices, rays, ++seed, false});
    }
    return configs;
}

CaseCounts runWatertightCase(const WatertightConfig &config, int threads) {
    Scene scene;
    scene.meshes.push_back(makeWatertightSphere(config));
    const TriangleMesh &mesh = scene.meshes[0];
    const Tracer tracer(scene);
    // Triangles around each vertex (compressed rows), for the duplicate count.
    std::vector<uint32_t> fanStart(mesh.positions.size() + 1, 0), fan;
    for (const glm::uvec3 &tri : mesh.indices)
        for (int k = 0; k < 3; ++k) ++fanStart[tri[k] + 1];
    for (std::size_t v = 1; v < fanStart.size(); ++v) fanStart[v] += fanStart[v - 1];
    fan.resize(fanStart.back());
    {
        std::vector<uint32_t> fill(fanStart.begin(), fanStart.end() - 1);
        for (uint32_t t = 0; t < mesh.indices.size(); ++t)
            for (int k = 0; k < 3; ++k) fan[fill[mesh.indices[t][k]]++] = t;
    }
    // Jitter the origins well inside the surface: the UV sphere has r = 2, the jittered one r ≥ 1.
    const double jitter = config.mesh == SphereMesh::Uv200 ? 0.5 : 0.2;
    RayQuery query;
    if (config.clipLowerHalf) {
        query.addClip(ClipVolume::halfSpace({0.f, 0.f, 1.f}, float(config.center.z), ClipVolume::Keep::Inside));
    }
    // Targets this far above the clip plane are unambiguous even where float spacing is 1/64.
    const double clipMargin = 0.1;

    // Slices of 4096 rays: coarse enough that handing them out costs nothing next to tracing.
    return parallelCounts(config.rays, threads, 4096, [&](uint64_t begin, uint64_t end, CaseCounts &out) {
        std::vector<uint32_t> neighbours;
        for (uint64_t i = begin; i < end; ++i) {
            CaseRng rng(config.seed, i);
            // With the clip, random-direction rays start above the plane and rise, so their hit
            // point is clearly kept.
            const double lowestZ = config.clipLowerHalf && config.targets == SphereTargets::RandomDirections ? 0 : -1;
            const glm::vec3 origin(config.center + jitter * glm::dvec3{rng.uniform(-1, 1), rng.uniform(-1, 1),
                                                                       rng.uniform(lowestZ, 1)});
            glm::vec3 direction;
            for (;;) {
                if (config.targets == SphereTargets::RandomDirections) {
                    direction = glm::vec3(rng.unitVector());
                    if (config.clipLowerHalf) direction.z = std::fabs(direction.z) + 0.05f;
                    break;
                }
                const glm::uvec3 tri = mesh.indices[rng.next() % mesh.indices.size()];
                const int corner = int(rng.next() % 3);
                const glm::dvec3 a(mesh.positions[tri[corner]]), b(mesh.positions[tri[(corner + 1) % 3]]);
                const glm::vec3 target = config.targets == SphereTargets::Vertices
                                             ? glm::vec3(a)
                                             : glm::vec3(a + rng.uniform(0.02, 0.98) * (b - a));
                if (config.clipLowerHalf && double(target.z) < config.center.z + clipMargin) continue;
                direction = target - origin;
                break;
            }
            const Ray ray{origin, direction};
            Hit hit;
            const bool found = tracer.closestHit(ray, query, hit);
            ++out.rays;
            out.hash += hitHash(i, found, hit);
            if (!found) {
                ++out.failures;
                continue;
            }
            // Did a neighbour of the winning triangle report the same crossing as well?
            neighbours.clear();
            const glm::uvec3 won = mesh.indices[hit.primitive];
            for (int k = 0; k < 3; ++k)
                for (uint32_t f = fanStart[won[k]]; f < fanStart[won[k] + 1]; ++f)
                    if (fan[f] != hit.primitive) neighbours.push_back(fan[f]);
            std::sort(neighbours.begin(), neighbours.end());
            neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
            const WatertightRay wray(ray);
            for (const uint32_t t : neighbours) {
                const glm::uvec3 f = mesh.indices[t];
                TriangleHit th{};
                if (intersectTriangle(wray, mesh.positions[f.x], mesh.positions[f.y], mesh.positions[f.z],
                                      0.f, kInf, th) &&
                    ulpDistance(th.t, hit.t) <= 4) {
                    ++out.duplicates;
                    break;
                }
            }
        }
    });
}

// ---------------------------------------------------------------------------------------------
// Re-intersection

CaseCounts runReintersectionCase(uint32_t triangles, uint32_t raysPerHit, uint64_t seed, int threads) {
    // ±10^U(−8, 8) per coordinate, as pbrt-v4's shapes_test (with random signs on top).
    auto coordinate = [](CaseRng &rng) {
        const double magnitude = std::pow(10.0, rng.uniform(-8.0, 8.0));
        return (rng.next() & 1) ? magnitude : -magnitude;
    };
    // One triangle per slice: each builds a tracer and traces raysPerHit rays.
    return parallelCounts(triangles, threads, 1, [&](uint64_t begin, uint64_t end, CaseCounts &out) {
        for (uint64_t i = begin; i < end; ++i) {
            CaseRng rng(seed, i);
            Scene scene;
            TriangleMesh mesh;
            for (int k = 0; k < 3; ++k)
                mesh.positions.push_back(glm::vec3{float(coordinate(rng)), float(coordinate(rng)),
                                                   float(coordinate(rng))});
            mesh.indices = {{0, 1, 2}};
            scene.meshes.push_back(mesh);
            const Tracer tracer(scene);
            // A random point of the triangle, hit from a random origin.
            double b1 = rng.uniform(), b2 = rng.uniform();
            if (b1 + b2 > 1.0) {
                b1 = 1.0 - b1;
                b2 = 1.0 - b2;
            }
            const glm::dvec3 p0(mesh.positions[0]), p1(mesh.positions[1]), p2(mesh.positions[2]);
            const glm::vec3 target((1.0 - b1 - b2) * p0 + b1 * p1 + b2 * p2);
            const glm::vec3 origin{float(coordinate(rng)), float(coordinate(rng)), float(coordinate(rng))};
            const Ray ray{origin, target - origin};
            Hit hit;
            const bool found = tracer.closestHit(ray, {}, hit);
            out.hash += hitHash(i << 20, found, hit);
            if (!found) continue;
            const SurfaceInteraction si = tracer.interaction(ray, hit);
            for (uint32_t j = 0; j < raysPerHit; ++j) {
                const glm::vec3 w(rng.unitVector());
                const Ray spawned{offsetRayOrigin(si.position, si.positionError, si.geometricNormal, w), w};
                Hit again;
                const bool reHit = tracer.closestHit(spawned, {}, again);
                ++out.rays;
                out.failures += reHit;
                out.hash += mix64((i << 20 | j) ^ (uint64_t(std::bit_cast<uint32_t>(spawned.origin.x)) << 1) ^
                                  (uint64_t(std::bit_cast<uint32_t>(spawned.origin.y)) << 17) ^
                                  (uint64_t(std::bit_cast<uint32_t>(spawned.origin.z)) << 33));
                if (reHit) out.hash += hitHash(i << 20 | j, true, again);
            }
        }
    });
}

// ---------------------------------------------------------------------------------------------
// Layer-gap sweep

std::vector<double> layerGapFractions() { return {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7}; }

std::vector<double> layerGapTranslations() { return {0.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7}; }

bool layerGapPassRequired(double gap, double translation) {
    const float x = float(std::fabs(translation) + kLayerGapCubeSize);
    const double ulp = double(nextFloatUp(x)) - double(x);
    return gap * kLayerGapCubeSize >= 32.0 * ulp;
}

Scene makeLayerGapScene(double gap, double translation) {
    const glm::dvec3 t(translation);
    const double half = 0.5 * kLayerGapCubeSize;
    const double innerHalf = half - gap * kLayerGapCubeSize;
    Scene scene;
    TriangleMesh outer = test::makeBoxMesh(glm::vec3(t - half), glm::vec3(t + half));
    outer.name = "outer";
    outer.layer = 0;
    TriangleMesh inner = test::makeBoxMesh(glm::vec3(t - innerHalf), glm::vec3(t + innerHalf));
    inner.name = "inner";
    inner.layer = 1;
    scene.meshes = {outer, inner};
    return scene;
}

LayerGapCell runLayerGapCell(double gap, double translation, uint32_t raysPerCheck, uint64_t seed) {
    LayerGapCell cell;
    cell.gap = gap;
    cell.translation = translation;
    cell.required = layerGapPassRequired(gap, translation);
    const Scene scene = makeLayerGapScene(gap, translation);
    const Tracer tracer(scene);
    const glm::dvec3 t(translation);
    const double half = 0.5 * kLayerGapCubeSize;
    const double innerHalf = half - gap * kLayerGapCubeSize;
    uint64_t query = 0;
    // Traces and returns the first layer hit (−1 for a miss), counting non-finite results.
    auto firstLayer = [&](const Ray &ray, const RayQuery &q, Hit &hit) {
        ++cell.rays;
        const bool found = tracer.closestHit(ray, q, hit);
        cell.hash += hitHash(query++, found, hit);
        if (found && (!std::isfinite(hit.t) || !isFinite(ray.at(hit.t)))) ++cell.nonFinite;
        return found ? int(hit.layer) : -1;
    };
    for (uint32_t i = 0; i < raysPerCheck; ++i) {
        CaseRng rng(seed, i);
        // A face of the cube: axis and side, and its in-face axes.
        const int axis = int(rng.next() % 3);
        const double side = (rng.next() & 1) ? 1.0 : -1.0;
        const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
        auto onFace = [&](double distance, double u, double v) {
            glm::dvec3 p(0.0);
            p[axis] = side * distance;
            p[ua] = u;
            p[va] = v;
            return t + p;
        };
        // Primary ray from outside onto the face, away from its rim, so the refracted ray meets
        // the inner cube's face behind it.
        // One draw per statement: the order of function arguments is unspecified, and the
        // digest must not depend on the compiler.
        const double originU = rng.uniform(-0.4, 0.4);
        const double originV = rng.uniform(-0.4, 0.4);
        const double targetU = rng.uniform(-0.3, 0.3) * kLayerGapCubeSize;
        const double targetV = rng.uniform(-0.3, 0.3) * kLayerGapCubeSize;
        const glm::vec3 origin(onFace(3.0 * kLayerGapCubeSize, originU, originV));
        const glm::vec3 target(onFace(half, targetU, targetV));
        const Ray primary{origin, glm::normalize(target - origin)};
        Hit hit;
        if (firstLayer(primary, {}, hit) != 0) {
            ++cell.primaryWrong;
        } else {
            const SurfaceInteraction si = tracer.interaction(primary, hit);
            glm::vec3 refracted;
            if (refract(primary.direction, si.geometricNormal, 1.f / 1.5f, refracted)) {
                const Ray ray{offsetRayOrigin(si.position, si.positionError, si.geometricNormal, refracted),
                              refracted};
                Hit next;
                if (firstLayer(ray, {}, next) != 1) ++cell.refractionWrong;
            }
            // A point light inside the inner cube: the shadow segment must end on layer 1.
            const glm::vec3 light(t + 0.5 * innerHalf * glm::dvec3{rng.uniform(-1, 1), rng.uniform(-1, 1),
                                                                   rng.uniform(-1, 1)});
            const glm::vec3 toLight = light - si.position;
            const float distance = glm::length(toLight);
            const glm::vec3 dir = toLight / distance;
            const Ray shadow{offsetRayOrigin(si.position, si.positionError, si.geometricNormal, dir), dir};
            RayQuery q;
            q.tMax = distance;
            Hit blocker;
            if (firstLayer(shadow, q, blocker) != 1 || !tracer.anyHit(shadow, q)) ++cell.shadowWrong;
        }
        // A ray from near the centre hits the outer layer from inside (the inner cube masked
        // out) and is reflected back: it must meet the inner cube, not the outer layer again.
        const glm::vec3 centre(t + 0.05 * innerHalf * glm::dvec3{rng.uniform(-1, 1), rng.uniform(-1, 1),
                                                                 rng.uniform(-1, 1)});
        const double wallU = rng.uniform(-0.25, 0.25) * kLayerGapCubeSize;
        const double wallV = rng.uniform(-0.25, 0.25) * kLayerGapCubeSize;
        const glm::vec3 wallPoint(onFace(half, wallU, wallV));
        const Ray outward{centre, glm::normalize(wallPoint - centre)};
        RayQuery outerOnly;
        outerOnly.layerMask = layerBit(0);
        if (firstLayer(outward, outerOnly, hit) != 0) {
            ++cell.reflectionWrong;
        } else {
            const SurfaceInteraction si = tracer.interaction(outward, hit);
            const glm::vec3 n = si.geometricNormal;
            const glm::vec3 r = outward.direction - 2.f * glm::dot(n, outward.direction) * n;
            const Ray reflected{offsetRayOrigin(si.position, si.positionError, n, r), r};
            Hit next;
            if (firstLayer(reflected, {}, next) != 1) ++cell.reflectionWrong;
        }
    }
    return cell;
}

std::string formatLayerGapMap(const std::vector<LayerGapCell> &cells) {
    const std::vector<double> gaps = layerGapFractions(), translations = layerGapTranslations();
    std::ostringstream os;
    os << "layer-gap pass map (rows: gap s·size, columns: translation T; ok = pass, FAIL = "
          "required and failed, - = failed where not required, [x] = required)\n";
    char buf[64];
    os << "   s \\ T ";
    for (const double t : translations) {
        std::snprintf(buf, sizeof buf, "%9.0e", t);
        os << buf;
    }
    os << '\n';
    for (const double s : gaps) {
        std::snprintf(buf, sizeof buf, "%8.0e ", s);
        os << buf;
        for (const double t : translations) {
            const auto it = std::find_if(cells.begin(), cells.end(),
                                         [&](const LayerGapCell &c) { return c.gap == s && c.translation == t; });
            std::string mark = "?";
            if (it != cells.end()) {
                mark = it->pass() ? "ok" : (it->required ? "FAIL" : "-");
                if (it->required) mark = "[" + mark + "]";
            }
            std::snprintf(buf, sizeof buf, "%9s", mark.c_str());
            os << buf;
        }
        os << '\n';
    }
    return os.str();
}

} // namespace mvcl::robustness
