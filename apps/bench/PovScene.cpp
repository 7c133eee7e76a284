#include "PovScene.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <string>

namespace mvcl::bench {

namespace {

double clamp01(float v) { return std::isfinite(v) ? std::clamp(double(v), 0.0, 1.0) : 0.0; }

glm::dvec3 nonNegative(const glm::vec3 &v) {
    glm::dvec3 out;
    for (int c = 0; c < 3; ++c) out[c] = std::isfinite(v[c]) ? std::max(double(v[c]), 0.0) : 0.0;
    return out;
}

bool anyPositive(const glm::dvec3 &v) { return v.x > 0.0 || v.y > 0.0 || v.z > 0.0; }

/// `v` as text at its end: a value that is exactly a float (most are: they come from the scene)
/// in the fewest digits that read back as that float, others in 10 significant digits.
char *appendNumber(char *out, char *end, double v) {
    const float f = float(v);
    if (double(f) == v) return std::to_chars(out, end, f).ptr;
    return std::to_chars(out, end, v, std::chars_format::general, 10).ptr;
}

std::string number(double v) {
    char text[40];
    return std::string(text, appendNumber(text, text + sizeof text, v));
}

/// "<x, y, z>" at the end of `out`.
char *appendVector(char *out, char *end, const glm::dvec3 &v) {
    *out++ = '<';
    for (int c = 0; c < 3; ++c) {
        out = appendNumber(out, end, v[c]);
        if (c < 2) *out++ = ',', *out++ = ' ';
    }
    *out++ = '>';
    return out;
}

std::string vec(const glm::dvec3 &v) {
    char text[112];
    return std::string(text, appendVector(text, text + sizeof text, v));
}

std::string rgb(const glm::dvec3 &v) { return "rgb " + vec(v); }

/// POV-Ray strings and comments: keep names printable and free of quotes and line breaks.
std::string plain(const std::string &text) {
    std::string out;
    for (const char c : text) out.push_back(c == '"' || c == '\\' || (unsigned char)(c) < 0x20 ? '_' : c);
    return out;
}

bool hasTexture(const Material &m) {
    if (!m.hasMetallicRoughness) return false;
    const MetallicRoughness &mr = m.metallicRoughness;
    return mr.baseColorTexture.isSet() || mr.metallicRoughnessTexture.isSet() || mr.normalTexture.isSet() ||
           mr.occlusionTexture.isSet() || mr.emissiveTexture.isSet();
}

/// A point light's colour and fade in POV-Ray, whose attenuation is 2 / (1 + (r / fade_distance)^fade_power).
struct PovPointLight {
    glm::dvec3 color{0.0};
    double fadeDistance = 0.0; ///< 0: no fading
    int fadePower = 0;
    std::string note; ///< how it differs from ours, if it does
};

/// Ours is I / (c + l·r + q·r²). With c > 0 and only one of l, q, POV's fade is the same function:
/// colour I / (2c), fade_distance c / l (power 1) or √(c / q) (power 2). Pure inverse square
/// (c = 0, as glTF's point lights) takes c = q·ε² with ε a thousandth of the scene's size, so it is
/// off by (ε / r)² (a millionth of the light at the scene's distance). l and q both non-zero: the
/// attenuation at `typicalDistance` is folded into the colour.
PovPointLight povPointLight(const Light &light, double typicalDistance, double sceneSize) {
    PovPointLight out;
    const glm::dvec3 intensity = nonNegative(light.intensity);
    const double c = std::max(0.0, double(light.constantAttenuation));
    const double l = std::max(0.0, double(light.linearAttenuation));
    const double q = std::max(0.0, double(light.quadraticAttenuation));
    if (l == 0.0 && q == 0.0) {
        out.color = c > 0.0 ? intensity / c : glm::dvec3(0.0);
        if (!(c > 0.0)) out.note = "no attenuation term: the light is off, as ours is";
        return out;
    }
    if (l > 0.0 && q > 0.0) {
        const double d = c + l * typicalDistance + q * typicalDistance * typicalDistance;
        out.color = intensity / d;
        out.note = "attenuation " + number(c) + " + " + number(l) + " r + " + number(q) +
                   " r^2 taken at the scene's centre (r = " + number(typicalDistance) + ") and folded into its colour";
        return out;
    }
    double constant = c;
    if (!(constant > 0.0)) {
        const double epsilon = 1e-3 * sceneSize;
        constant = l > 0.0 ? l * epsilon : q * epsilon * epsilon;
        out.note = "no constant attenuation: POV's fade is given one of " + number(constant) +
                   " (off by (" + number(epsilon) + " / r)^" + (l > 0.0 ? "1" : "2") + ")";
    }
    out.color = intensity / (2.0 * constant);
    out.fadePower = l > 0.0 ? 1 : 2;
    out.fadeDistance = l > 0.0 ? constant / l : std::sqrt(constant / q);
    return out;
}

/// One line per vertex, normal or triangle: big meshes go out in chunks, not one write each.
class ChunkedWriter {
public:
    explicit ChunkedWriter(std::ostream &out) : m_out(out) { m_buffer.reserve(kChunk + 256); }
    ~ChunkedWriter() { flush(); }
    void append(const char *text, std::size_t n) {
        m_buffer.append(text, n);
        if (m_buffer.size() >= kChunk) flush();
    }
    void append(const std::string &text) { append(text.data(), text.size()); }
    void flush() {
        m_out.write(m_buffer.data(), std::streamsize(m_buffer.size()));
        m_buffer.clear();
    }

private:
    static constexpr std::size_t kChunk = 1 << 20;
    std::ostream &m_out;
    std::string m_buffer;
};

void writeVectors(ChunkedWriter &w, const char *block, const std::vector<glm::vec3> &values, const glm::dvec3 &offset) {
    w.append(std::string("  ") + block + " { " + std::to_string(values.size()) + ",\n");
    char line[128];
    for (std::size_t i = 0; i < values.size(); ++i) {
        char *end = std::copy_n("    ", 4, line);
        end = appendVector(end, line + sizeof line, glm::dvec3(values[i]) + offset);
        if (i + 1 < values.size()) *end++ = ',';
        *end++ = '\n';
        w.append(line, std::size_t(end - line));
    }
    w.append("  }\n");
}

std::string materialName(std::size_t index) { return "MvclMaterial" + std::to_string(index); }

} // namespace

PovMaterial povMaterialOf(const Material &m, const glm::vec3 &ambientLight) {
    PovMaterial p;
    const std::string name = "material '" + plain(m.name) + "': ";
    const double t = clamp01(m.transparency);
    const glm::dvec3 diffuse = nonNegative(m.diffuse);
    const glm::dvec3 ambient = nonNegative(m.ambient) * nonNegative(ambientLight);
    const glm::dvec3 emission = nonNegative(m.emission);
    // POV multiplies ambient, diffuse and emission by the pigment: the pigment is our diffuse
    // colour, and the other two are divided by it. A material without diffuse colour (a smooth
    // metal) takes its ambient colour as the pigment, with diffuse 0.
    if (anyPositive(diffuse)) {
        p.pigment = diffuse;
        p.diffuse = 1.0;
    } else if (anyPositive(ambient)) {
        p.pigment = ambient;
    } else if (anyPositive(emission)) {
        p.pigment = emission;
    } else {
        p.diffuse = 1.0;
    }
    p.transmit = t;
    bool ambientLost = false, emissionLost = false;
    for (int c = 0; c < 3; ++c) {
        if (p.pigment[c] > 0.0)
            p.ambient[c] = ambient[c] / p.pigment[c];
        else
            ambientLost = ambientLost || ambient[c] > 0.0;
        // POV dims emission by the opacity 1 − T as it does ambient and diffuse; ours is not dimmed.
        if (p.pigment[c] > 0.0 && t < 1.0)
            p.emission[c] = emission[c] / (p.pigment[c] * (1.0 - t));
        else
            emissionLost = emissionLost || emission[c] > 0.0;
    }
    if (ambientLost) p.lost.push_back(name + "ambient in a colour channel without diffuse colour is lost");
    if (emissionLost) p.lost.push_back(name + "emission in a colour channel without pigment (or fully transparent) is lost");

    const double ks = std::isfinite(m.specular) ? std::max(0.0, double(m.specular)) : 0.0;
    p.specular = ks * (1.0 - t);
    p.roughness = 1.0 / std::max(1.0, std::isfinite(m.shininess) ? double(m.shininess) : 1.0);
    const glm::dvec3 tint = nonNegative(m.specularColor);
    if (p.specular > 0.0 && tint != glm::dvec3(1.0))
        p.lost.push_back(name + "the highlight's tint " + vec(tint) + " is not converted (POV's highlights are white)");

    const glm::dvec3 mirror = (std::isfinite(m.reflectivity) ? std::max(0.0, double(m.reflectivity)) : 0.0) * tint;
    p.reflectionMin = mirror;
    p.reflectionMax = mirror;
    if (t > 0.0) {
        p.fresnel = true;
        p.reflectionMax = mirror + glm::dvec3(t);
        p.ior = std::isfinite(m.ior) ? std::max(1.0, double(m.ior)) : 1.0;
    }
    if (hasTexture(m)) p.lost.push_back(name + "textures are not converted (its factors only)");
    if (m.alphaMode == AlphaMode::Mask) p.lost.push_back(name + "its alpha mask is not converted (opaque here)");
    return p;
}

double povHorizontalAngle(double verticalFovDegrees, double aspect) {
    const double radians = std::numbers::pi / 180.0;
    return 2.0 * std::atan(std::tan(0.5 * verticalFovDegrees * radians) * aspect) / radians;
}

PovSceneSummary writePovScene(std::ostream &out, const Scene &scene, const Camera &camera,
                              const PovSceneOptions &options) {
    PovSceneSummary summary;
    const glm::dvec3 origin = scene.worldOrigin;
    const auto world = [&](const glm::vec3 &p) { return glm::dvec3(p) + origin; };
    // Loaders always leave a material; a scene made by hand may not, and gets the default one.
    const std::vector<Material> materials = scene.materials.empty() ? std::vector<Material>(1) : scene.materials;
    const auto materialOf = [&](uint32_t index) -> std::size_t { return index < materials.size() ? index : 0; };

    // The materials in use, mapped first: what they lose goes into the header.
    std::set<std::size_t> used;
    for (const TriangleMesh &m : scene.meshes)
        if (!m.indices.empty()) used.insert(materialOf(m.material));
    for (const Sphere &s : scene.spheres) used.insert(materialOf(s.material));
    for (const Plane &p : scene.planes) used.insert(materialOf(p.material));
    std::vector<PovMaterial> povMaterials(materials.size());
    bool transparentMesh = false;
    for (const std::size_t i : used) {
        povMaterials[i] = povMaterialOf(materials[i], scene.ambientLight);
        for (const std::string &lost : povMaterials[i].lost) summary.notes.push_back(lost);
    }
    for (const TriangleMesh &m : scene.meshes)
        transparentMesh = transparentMesh || (!m.indices.empty() && povMaterials[materialOf(m.material)].fresnel);
    if (std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const TriangleMesh &m) {
            return !m.indices.empty() && m.normals.size() == m.positions.size();
        }))
        summary.notes.push_back("vertex normals: where an interpolated normal and its triangle disagree, POV turns "
                                "the normal toward the eye and lights by it alone, we keep it on the triangle's side "
                                "(or take the triangle's normal) and light only where both face the light, so a few "
                                "pixels at silhouettes and terminators are lit differently");
    if (transparentMesh)
        summary.notes.push_back("a transparent mesh: we tell entering from leaving by the mesh's closure and "
                                "normals, POV by the interiors a ray is in");

    const Bounds3f bounds = scene.bounds();
    const glm::dvec3 center = bounds.isEmpty() ? origin : world(bounds.center());
    const double size = bounds.isEmpty() ? 1.0 : std::max(1e-6, double(glm::length(bounds.extent())));
    std::vector<PovPointLight> pointLights(scene.lights.size());
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light &light = scene.lights[i];
        if (light.type != LightType::Point) continue;
        pointLights[i] = povPointLight(light, glm::length(world(light.position) - center), size);
        if (!pointLights[i].note.empty())
            summary.notes.push_back("light '" + plain(light.name) + "': " + pointLights[i].note);
    }

    ChunkedWriter w(out);
    const std::string sizeText = std::to_string(options.width) + "x" + std::to_string(options.height);
    w.append("// POV-Ray 3.7 scene written by `mvcl-bench pov` from " + plain(options.source) + ", framed for " +
             sizeText + ".\n");
    w.append("//   povray +I<this file> +W" + std::to_string(options.width) + " +H" + std::to_string(options.height) +
             " -A -J0 +FN -D -P File_Gamma=sRGB\n");
    w.append("//   mvcl-render " + plain(options.source) + " --size " + sizeText + " --spp 1 " + options.renderArgs +
             "\n");
    w.append("// World space, the file's units (our scene space is world - " + vec(origin) + ").\n");
    w.append("// Not converted: textures (every material is its factors only) and alpha masks (MASK materials\n"
             "// render opaque here).\n");
    w.append("// Approximate wherever light goes through a surface: Fresnel (ours Schlick's, POV the exact\n"
             "// formula); the refracted share (ours T*(1-F), POV's conserve_energy T*(1-R*S-T*F)); total\n"
             "// internal reflection (we mirror with weight R+T, POV at full weight).\n");
    if (summary.notes.empty()) {
        w.append("// Nothing else in this scene is approximated.\n");
    } else {
        w.append("// Differs in this scene:\n");
        for (const std::string &note : summary.notes) w.append("//   " + note + "\n");
    }
    w.append("// Mapping (our Phong/Whitted term -> POV): A*ambientLight -> pigment C times finish ambient\n"
             "// A*ambientLight/C; P -> pigment C = P, diffuse 1; Ks, Ps -> specular Ks*(1-T), roughness 1/Ps;\n"
             "// reflectivity R, tint S -> reflection R*S; transparency T, ior -> rgbt <C, T>, reflection\n"
             "// {R*S, R*S+T fresnel on}, conserve_energy, interior ior; emission E -> emission E/(C*(1-T));\n"
             "// our bounce limit + 1 -> max_trace_level; no pruning by weight -> adc_bailout 0.\n");
    w.append("#version 3.7;\n\n");

    const int maxTraceLevel = std::clamp(options.maxDepth + 1, 1, 256);
    w.append("global_settings {\n  assumed_gamma 1.0  // linear shading, as ours; render with File_Gamma=sRGB\n"
             "  ambient_light rgb 1  // the scene's ambient light is in each finish's ambient\n"
             "  max_trace_level " +
             std::to_string(maxTraceLevel) + "  // " + std::to_string(options.maxDepth) +
             " bounces after the primary hit\n  adc_bailout 0\n}\n\n");
    w.append("background { " + rgb(nonNegative(scene.background)) + " }\n\n");

    const glm::mat3 &axes = camera.sceneFromCamera(); // right, up, backward
    w.append("#declare Aspect = image_width / image_height;  // framed for " +
             number(double(options.width) / double(options.height)) + "\n");
    w.append("#declare VFov = " + number(camera.verticalFovDegrees()) + ";  // our vertical field of view, degrees\n");
    w.append("camera {  // right-handed, as ours (right -x); angle is POV's horizontal field of view\n"
             "  perspective\n  location " +
             vec(world(camera.eye())) + "\n  right -x * Aspect\n  up y\n" +
             "  angle 2 * degrees(atan(tan(radians(VFov / 2)) * Aspect))  // " +
             number(povHorizontalAngle(camera.verticalFovDegrees(), double(options.width) / double(options.height))) +
             " here\n  sky " + vec(glm::dvec3(axes[1])) + "\n  look_at " + vec(world(camera.target())) + "\n}\n\n");

    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light &light = scene.lights[i];
        if (light.type == LightType::Directional) {
            glm::dvec3 d(light.direction);
            d = glm::length(d) > 0.0 ? glm::normalize(d) : glm::dvec3(0.0, -1.0, 0.0);
            w.append("light_source {  // '" + plain(light.name) + "', directional\n  " + vec(center - 1e4 * size * d) +
                     "\n  color " + rgb(nonNegative(light.intensity)) + "\n  parallel\n  point_at " + vec(center) +
                     "\n}\n");
        } else {
            const PovPointLight &p = pointLights[i];
            w.append("light_source {  // '" + plain(light.name) + "', point\n  " + vec(world(light.position)) +
                     "\n  color " + rgb(p.color) + "\n");
            if (p.fadePower > 0)
                w.append("  fade_distance " + number(p.fadeDistance) + "\n  fade_power " + std::to_string(p.fadePower) +
                         "\n");
            w.append("}\n");
        }
        ++summary.lights;
    }
    w.append("\n");

    for (const std::size_t i : used) {
        const PovMaterial &p = povMaterials[i];
        std::string text = "#declare " + materialName(i) + " = material {  // '" + plain(materials[i].name) +
                           "'\n  texture {\n    pigment { ";
        text += p.transmit > 0.0 ? "rgbt <" + number(p.pigment.x) + ", " + number(p.pigment.y) + ", " +
                                       number(p.pigment.z) + ", " + number(p.transmit) + ">"
                                 : rgb(p.pigment);
        text += " }\n    finish {\n      ambient " + rgb(p.ambient) + "\n      diffuse " + number(p.diffuse) + "\n";
        if (anyPositive(p.emission)) text += "      emission " + rgb(p.emission) + "\n";
        if (p.specular > 0.0)
            text += "      specular " + number(p.specular) + " roughness " + number(p.roughness) + "\n";
        if (p.fresnel)
            text += "      reflection { " + rgb(p.reflectionMin) + ", " + rgb(p.reflectionMax) +
                    " fresnel on }\n      conserve_energy\n";
        else if (anyPositive(p.reflectionMin))
            text += "      reflection { " + rgb(p.reflectionMin) + " }\n";
        text += "    }\n  }\n";
        if (p.fresnel) text += "  interior { ior " + number(p.ior) + " }\n";
        text += "}\n";
        w.append(text);
    }
    summary.materials = used.size();
    w.append("\n");

    char line[96];
    for (const TriangleMesh &m : scene.meshes) {
        if (m.indices.empty()) continue;
        const std::size_t material = materialOf(m.material);
        w.append("// mesh '" + plain(m.name) + "', layer " + std::to_string(m.layer) + ", material '" +
                 plain(materials[material].name) + "', " + std::to_string(m.indices.size()) + " triangles\n");
        w.append("mesh2 {\n");
        writeVectors(w, "vertex_vectors", m.positions, origin);
        if (m.normals.size() == m.positions.size()) writeVectors(w, "normal_vectors", m.normals, glm::dvec3(0.0));
        w.append("  face_indices { " + std::to_string(m.indices.size()) + ",\n");
        for (std::size_t t = 0; t < m.indices.size(); ++t) {
            const glm::uvec3 &f = m.indices[t];
            const int n = std::snprintf(line, sizeof line, "    <%u, %u, %u>%s\n", f.x, f.y, f.z,
                                        t + 1 < m.indices.size() ? "," : "");
            w.append(line, std::size_t(n));
        }
        w.append("  }\n  material { " + materialName(material) + " }\n}\n");
        ++summary.meshes;
        summary.triangles += m.indices.size();
    }
    for (const Sphere &s : scene.spheres) {
        w.append("sphere {  // '" + plain(s.name) + "', layer " + std::to_string(s.layer) + "\n  " +
                 vec(world(s.center)) + ", " + number(s.radius) + "\n  material { " +
                 materialName(materialOf(s.material)) + " }\n}\n");
        ++summary.spheres;
    }
    for (const Plane &p : scene.planes) {
        // dot(n, p_scene) = offset  <=>  dot(n, p_world) = offset + dot(n, origin)
        const glm::dvec3 n(p.normal);
        w.append("plane {  // '" + plain(p.name) + "', layer " + std::to_string(p.layer) + "\n  " + vec(n) + ", " +
                 number(double(p.offset) + glm::dot(n, origin)) + "\n  material { " +
                 materialName(materialOf(p.material)) + " }\n}\n");
        ++summary.planes;
    }
    w.flush();
    return summary;
}

} // namespace mvcl::bench
