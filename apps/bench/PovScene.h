#pragma once
/// \file PovScene.h
/// A loaded scene and a camera as a POV-Ray 3.7 scene that traces the same picture, for
/// `mvcl-bench pov` (PovBench.cpp). POV-Ray is a recursive Whitted-style tracer, so every term of
/// our integrator has a counterpart there:
///
///   ours (Material, WhittedIntegrator)         POV-Ray 3.7
///   A·ambientLight                             pigment C × finish ambient (A·ambientLight / C)
///   P·(L·N)                                    pigment C = P, finish diffuse 1 (brilliance 1)
///   Ks·(N·H)^Ps                                specular Ks, roughness 1/Ps (Blinn-Phong in both)
///   reflectivity R, tint S                     reflection { rgb R·S }
///   transparency T: local·(1 − T), T·F to the  rgbt <C, T> (POV scales ambient, diffuse and
///   reflected ray, T·(1 − F) to the refracted  emission by 1 − T), reflection { R·S, R·S + T
///   (Schlick F)                                fresnel on } with conserve_energy, interior ior
///   the highlight of a see-through surface     specular Ks·(1 − T): POV does not scale highlights
///   scaled by 1 − T                            by opacity, so the factor goes into Ks
///   emission E (not scaled by 1 − T)           finish emission E / (C·(1 − T))
///   point light, D = c + l·r + q·r²            light_source, colour I / c (l, q: see notes)
///   directional light                          parallel light_source far away
///   maxDepth bounces after the primary hit     max_trace_level maxDepth + 1 (POV counts the
///                                              primary ray), adc_bailout 0 (we never prune)
///   linear shading, sRGB files                 assumed_gamma 1; render with File_Gamma=sRGB
///
/// Where no exact counterpart exists the file says so in its header comment: textures and alpha
/// masks (never converted: factors only, MASK materials come out opaque), a metal's tinted
/// highlight (POV's are white), ambient or emission in a colour channel whose pigment is zero,
/// point lights whose attenuation POV's fade cannot express, and what differs by design: POV's
/// exact Fresnel against our Schlick, its conserve_energy (refracted T·(1 − R·S − T·F), ours
/// T·(1 − F)), total internal reflection (POV mirrors at full weight, we with R + T), and vertex
/// normals that disagree with their triangle (POV turns them toward the eye and lights by them
/// alone; we keep the triangle's side and light only where the triangle faces the light too).

#include <mvcl/model/Material.h>
#include <mvcl/model/Scene.h>
#include <mvcl/view/Camera.h>

#include <glm/vec3.hpp>

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace mvcl::bench {

/// One material as POV-Ray finish, pigment and interior values.
struct PovMaterial {
    glm::dvec3 pigment{0.0};    ///< pigment colour C
    double transmit = 0.0;      ///< rgbt's t = our transparency T
    double diffuse = 0.0;       ///< finish diffuse (1, or 0 when C carries only the ambient term)
    glm::dvec3 ambient{0.0};    ///< finish ambient colour (times C and POV's ambient_light 1)
    glm::dvec3 emission{0.0};   ///< finish emission colour (times C and 1 − T)
    double specular = 0.0;      ///< finish specular
    double roughness = 1.0;     ///< finish roughness = 1 / Ps
    glm::dvec3 reflectionMin{0.0}; ///< reflection at normal incidence (or always, without fresnel)
    glm::dvec3 reflectionMax{0.0}; ///< reflection at grazing incidence (fresnel on)
    bool fresnel = false;       ///< transparent: fresnel on, conserve_energy and an interior ior
    double ior = 1.0;
    /// What the mapping could not carry over, in words (empty when it is exact).
    std::vector<std::string> lost;
};

/// The POV-Ray terms of `material` lit by a scene ambient light `ambientLight`.
PovMaterial povMaterialOf(const Material &material, const glm::vec3 &ambientLight);

/// POV-Ray's camera `angle` (horizontal, degrees) for our vertical field of view and an aspect
/// ratio width / height.
double povHorizontalAngle(double verticalFovDegrees, double aspect);

struct PovSceneOptions {
    std::string source;      ///< what the scene was loaded from (for the header comment)
    int width = 800;         ///< the view the camera was chosen for
    int height = 600;
    int maxDepth = 8;        ///< our bounces after the primary hit
    std::string renderArgs;  ///< the matching mvcl-render camera options (for the header comment)
};

struct PovSceneSummary {
    std::size_t meshes = 0;
    std::size_t triangles = 0;
    std::size_t spheres = 0;
    std::size_t planes = 0;
    std::size_t lights = 0;
    std::size_t materials = 0;
    /// Scene-specific approximations, also written into the file's header comment.
    std::vector<std::string> notes;
};

/// Writes `scene` seen through `camera` (scene space, as mvcl::Camera is) as a POV-Ray 3.7 scene
/// in world space (scene space + Scene::worldOrigin): triangle meshes as mesh2 (with their
/// per-vertex normals when they have them), spheres, planes, point and directional lights, the
/// scene's ambient light and background, the camera and one POV material per material used.
PovSceneSummary writePovScene(std::ostream &out, const Scene &scene, const Camera &camera,
                              const PovSceneOptions &options);

} // namespace mvcl::bench
