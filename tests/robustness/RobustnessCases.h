#pragma once
// Generators and runners of the robustness catalogue cases that both the GoogleTest suite
// (tests/robustness/*Test.cpp) and the build-flag digest (mvcl-robustness-digest) run, so that the
// digest compares builds on exactly the rays the tests check.
//
// Everything random here comes from CaseRng (splitmix64 on integers, no <random> distribution):
// the same seed gives bit-identical rays with any compiler, standard library, optimisation level
// and thread count.

#include <mvcl/model/Scene.h>
#include <mvcl/model/TriangleMesh.h>
#include <mvcl/tracer/Hit.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mvcl::robustness {

/// Counter-based random numbers: stream (seed, index) is independent of every other stream.
class CaseRng {
public:
    CaseRng(uint64_t seed, uint64_t stream);
    uint64_t next();
    /// Uniform in [0, 1) with 53 random bits.
    double uniform();
    /// Uniform in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    /// Uniform on the unit sphere (rejection from the cube, so no libm call).
    glm::dvec3 unitVector();

private:
    uint64_t m_state;
};

/// splitmix64 finaliser: a 64-bit mix for hashes.
uint64_t mix64(uint64_t x);
/// Order-independent hash of one ray's result: add the returned values of every ray together.
uint64_t hitHash(uint64_t rayIndex, bool found, const Hit &hit);

/// What one case measured.
struct CaseCounts {
    uint64_t rays = 0;       ///< queries traced
    uint64_t failures = 0;   ///< leaks, self-hits or wrong layers (the case says which)
    uint64_t duplicates = 0; ///< rays whose crossing more than one triangle reported
    uint64_t hash = 0;       ///< sum of hitHash() over every query: same rays, same hits
};

// ---------------------------------------------------------------------------------------------
// Cases 1–3 (and 22): watertightness of closed tessellated spheres.

enum class SphereMesh {
    Uv200,             ///< r = 2, 200 rings × 200 segments (Embree verify's WatertightTest)
    JitteredValence16, ///< 16 × 16, every vertex at a radius in [1, 6] (pbrt's Triangle.Watertight)
};
enum class SphereTargets {
    RandomDirections, ///< case 1: rays from inside in uniform directions
    Vertices,         ///< case 2: rays aimed exactly at mesh vertices
    EdgePoints,       ///< case 3: rays aimed at points on shared edges
};

struct WatertightConfig {
    std::string name;
    glm::dvec3 center{0.0};
    SphereMesh mesh = SphereMesh::Uv200;
    SphereTargets targets = SphereTargets::RandomDirections;
    uint64_t rays = 1000000;
    uint64_t seed = 1;
    /// Case 22: a keep-inside half-space clip through the centre ({z ≥ centre.z}); only targets
    /// with z clearly above it are used, so every ray must still hit.
    bool clipLowerHalf = false;
};

/// The sphere mesh of a configuration, positions rounded to float after adding the centre in
/// double (what a loader without re-centring produces).
TriangleMesh makeWatertightSphere(const WatertightConfig &config);

/// A cells × cells grid of quads, two triangles each, vertex (i, j) at vertexAt(i, j), i and j
/// in [0, cells].
template <class VertexAt>
TriangleMesh makeGridMesh(int cells, const VertexAt &vertexAt) {
    TriangleMesh grid;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) grid.positions.push_back(vertexAt(i, j));
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const uint32_t a = uint32_t(j * (cells + 1) + i), b = a + 1, c = a + uint32_t(cells) + 1, d = c + 1;
            grid.indices.push_back({a, b, d});
            grid.indices.push_back({a, d, c});
        }
    return grid;
}
/// Cases 1–3 at the origin and at (148376, 1234, −223423), `rays` rays each.
std::vector<WatertightConfig> standardWatertightConfigs(uint64_t rays);
/// Rays from inside the sphere through Tracer::closestHit. failures = leaks (no hit); duplicates
/// = rays for which a triangle sharing a vertex with the hit one reports the same crossing
/// (t within 4 ulps) through the scalar watertight kernel. Deterministic for any `threads`.
CaseCounts runWatertightCase(const WatertightConfig &config, int threads);

// ---------------------------------------------------------------------------------------------
// Case 14: re-intersection of spawned rays (pbrt-v4 Triangle.Reintersect).

/// `triangles` single-triangle scenes with coordinates ±10^U(−8, 8); a ray hits each at a random
/// point and `raysPerHit` rays in uniform directions are spawned with offsetRayOrigin().
/// failures = spawned rays that hit the triangle they leave. rays counts spawned rays only.
CaseCounts runReintersectionCase(uint32_t triangles, uint32_t raysPerHit, uint64_t seed, int threads);

// ---------------------------------------------------------------------------------------------
// Case 17: layer-gap sweep. An outer cube of edge `kLayerGapCubeSize` (layer 0) around an inner
// cube inset by gap·size on every side (layer 1), translated by (T, T, T) in double and rounded to
// float (no re-centring: this is the precision the float scene has at that distance).

inline constexpr double kLayerGapCubeSize = 1.0;

struct LayerGapCell {
    double gap = 0.0;         ///< s: the gap is s·size
    double translation = 0.0; ///< T
    uint64_t rays = 0;        ///< queries checked
    uint64_t primaryWrong = 0;    ///< primary rays from outside whose first hit is not layer 0
    uint64_t refractionWrong = 0; ///< refracted rays from the outer hit not hitting layer 1 first
    uint64_t shadowWrong = 0;     ///< shadow rays to a light inside the inner cube not stopped by layer 1
    uint64_t reflectionWrong = 0; ///< rays reflected off the outer layer's inside not hitting layer 1
    uint64_t nonFinite = 0;       ///< non-finite t or hit point
    uint64_t hash = 0;
    bool required = false; ///< s·size ≥ 32·ulp(|T| + size): must pass
    bool pass() const {
        return primaryWrong == 0 && refractionWrong == 0 && shadowWrong == 0 &&
               reflectionWrong == 0 && nonFinite == 0;
    }
};

std::vector<double> layerGapFractions();    ///< 1e-1 … 1e-7
std::vector<double> layerGapTranslations(); ///< 0, 1e1 … 1e7
/// Whether the catalogue requires a pass: s·size ≥ 32·ulp_float(|T| + size).
bool layerGapPassRequired(double gap, double translation);
Scene makeLayerGapScene(double gap, double translation);
LayerGapCell runLayerGapCell(double gap, double translation, uint32_t raysPerCheck, uint64_t seed);
/// The (s, T) pass map as a text table: "ok" pass, "FAIL" required but failed, "-" failed
/// where not required.
std::string formatLayerGapMap(const std::vector<LayerGapCell> &cells);

} // namespace mvcl::robustness
