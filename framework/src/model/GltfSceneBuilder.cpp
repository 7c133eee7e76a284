#include "GltfSceneBuilder_p.h"

#include "GltfTangents_p.h"

#include <mvcl/model/MeshClosure.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mvcl::gltf {

namespace {

/// Upper bound on instanced triangles: a small file that instances a big mesh 10^5 times must
/// fail with a message, not exhaust memory.
constexpr std::size_t kMaxSceneTriangles = std::size_t(1) << 27;

/// A normal whose length is off by more than this is counted as "fixed" in the report (all
/// normals are renormalised in double anyway); a quaternion that far off gets a warning.
constexpr double kUnitTolerance = 1e-3;

/// Matrix columns whose cosine exceeds this count as sheared (float-rounded exports stay below).
constexpr double kOrthogonalityTolerance = 1e-4;

const char *modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    default: return "TRIANGLE_FAN";
    }
}

bool isFinite(const glm::dmat4 &m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool isFinite(const glm::vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 toVec3(const glm::dvec3 &v) { return glm::vec3(float(v.x), float(v.y), float(v.z)); }

} // namespace

GltfSceneBuilder::GltfSceneBuilder(GltfContext &context, const GltfValidator &validator,
                                   const GltfLoadOptions &options, Scene &scene)
    : m_context(context), m_model(context.model()), m_validator(validator), m_reader(validator),
      m_options(options), m_scene(scene) {}

void GltfSceneBuilder::build() {
    m_decoded.resize(m_model.meshes.size());
    for (std::size_t m = 0; m < m_model.meshes.size(); ++m) m_decoded[m].resize(m_model.meshes[m].primitives.size());
    traverse();
    finish();
}

// ---------------------------------------------------------------------------------------------
// Materials (built before by GltfMaterialBuilder, same indices as the file's)

uint32_t GltfSceneBuilder::defaultMaterial() {
    if (!m_defaultMaterial) {
        Material m; // the Material defaults: matte light grey
        m.name = "default";
        m_defaultMaterial = uint32_t(m_scene.materials.size());
        m_scene.materials.push_back(m);
    }
    return *m_defaultMaterial;
}

// ---------------------------------------------------------------------------------------------
// Node graph

glm::dmat4 GltfSceneBuilder::localTransform(int node) {
    const tinygltf::Node &n = m_model.nodes[std::size_t(node)];
    if (n.matrix.size() == 16) {
        if (!n.translation.empty() || !n.rotation.empty() || !n.scale.empty())
            m_context.warn(m_context.describeNode(node) + " has both matrix and TRS; the matrix is used");
        const glm::dmat4 m = glm::make_mat4(n.matrix.data()); // both column-major
        // Orthogonal columns ⇔ rotation·scale; anything else shears. It renders correctly as an
        // affine map, but glTF forbids it, so the user should know the exporter misbehaved.
        const auto orthogonal = [&m](int a, int b) {
            const glm::dvec3 ca(m[a]), cb(m[b]);
            return std::abs(glm::dot(ca, cb)) <= kOrthogonalityTolerance * glm::length(ca) * glm::length(cb);
        };
        if (!orthogonal(0, 1) || !orthogonal(0, 2) || !orthogonal(1, 2))
            m_context.warn(m_context.describeNode(node) +
                           " matrix shears (it is not translation·rotation·scale); used as given");
        return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (n.translation.size() == 3) t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
    if (n.rotation.size() == 4) {
        glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]); // glTF: x, y, z, w
        const double len = glm::length(q);
        if (!(len > 0.0)) m_context.fail(m_context.describeNode(node) + " has a zero rotation quaternion");
        if (std::abs(len - 1.0) > kUnitTolerance)
            m_context.warn(m_context.describeNode(node) + " rotation quaternion has length " + std::to_string(len) +
                           "; normalised");
        r = glm::mat4_cast(q / len);
    }
    if (n.scale.size() == 3) s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    return t * r * s;
}

void GltfSceneBuilder::traverse() {
    const std::size_t n = m_model.nodes.size();
    const std::vector<int> &parents = m_validator.parents();
    std::vector<glm::dmat4> world(n, glm::dmat4(1.0));
    // Explicit stack: the validator has proven the graph is a forest, so every node is reached
    // at most once, and depth only costs heap memory.
    std::vector<int> stack(m_validator.rootNodes().rbegin(), m_validator.rootNodes().rend());
    while (!stack.empty()) {
        const int node = stack.back();
        stack.pop_back();
        const int parent = parents[std::size_t(node)];
        glm::dmat4 &w = world[std::size_t(node)];
        w = parent < 0 ? localTransform(node) : world[std::size_t(parent)] * localTransform(node);
        if (!isFinite(w))
            m_context.fail(m_context.describeNode(node) + " has a non-finite world transform");
        const tinygltf::Node &nd = m_model.nodes[std::size_t(node)];
        if (nd.mesh >= 0) instantiateMesh(node, w);
        if (nd.camera >= 0) addCamera(node, w);
        if (nd.extensions.count("KHR_lights_punctual")) addLight(node, w);
        for (auto it = nd.children.rbegin(); it != nd.children.rend(); ++it) stack.push_back(*it);
    }
}

// ---------------------------------------------------------------------------------------------
// Meshes

void GltfSceneBuilder::decodeNormals(int accessor, DecodedPrimitive &out) {
    const std::vector<glm::vec3> raw = m_reader.readVec3(accessor);
    out.normals.resize(raw.size());
    std::vector<std::size_t> zero;
    bool warnedNonFinite = false;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        const glm::dvec3 v(raw[i]);
        const double len = isFinite(raw[i]) ? glm::length(v) : 0.0;
        if (!isFinite(raw[i]) && !warnedNonFinite) {
            m_context.warn(m_validator.describeAccessor(accessor) +
                           " has non-finite normals; they are replaced by face normals");
            warnedNonFinite = true;
        }
        if (!(len > 0.0)) {
            zero.push_back(i);
            ++m_context.report().nonUnitNormalsFixed;
            continue;
        }
        if (std::abs(len - 1.0) > kUnitTolerance) ++m_context.report().nonUnitNormalsFixed;
        out.normals[i] = toVec3(v / len);
    }
    if (zero.empty()) return;
    // Zero normals take the (area-weighted) normal of the faces around the vertex.
    std::vector<glm::dvec3> faceSum(out.positions.size(), glm::dvec3(0.0));
    for (const glm::uvec3 &t : out.triangles) {
        const glm::dvec3 a(out.positions[t.x]), b(out.positions[t.y]), c(out.positions[t.z]);
        const glm::dvec3 f = glm::cross(b - a, c - a);
        for (int k = 0; k < 3; ++k) faceSum[t[k]] += f;
    }
    for (std::size_t i : zero) {
        const double len = glm::length(faceSum[i]);
        out.normals[i] = len > 0.0 ? toVec3(faceSum[i] / len) : glm::vec3(0.f, 0.f, 1.f);
    }
}

const GltfSceneBuilder::DecodedPrimitive &GltfSceneBuilder::decode(int mesh, int primitive) {
    DecodedPrimitive &out = m_decoded[std::size_t(mesh)][std::size_t(primitive)];
    if (out.decoded) return out;
    out.decoded = true;
    const tinygltf::Primitive &prim = m_model.meshes[std::size_t(mesh)].primitives[std::size_t(primitive)];
    const std::string where = m_context.describeMesh(mesh) + " primitive " + std::to_string(primitive);
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        ++m_context.report().primitivesSkipped;
        m_context.warn(where + ": mode " + modeName(prim.mode) + " skipped (only triangles are ray traced)");
        return out;
    }
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) {
        ++m_context.report().primitivesSkipped;
        m_context.warn(where + " has no POSITION attribute and is skipped");
        return out;
    }
    out.positions = m_reader.readVec3(pos->second);
    for (std::size_t i = 0; i < out.positions.size(); ++i)
        if (!isFinite(out.positions[i]))
            m_context.fail(m_validator.describeAccessor(pos->second) + ": position " + std::to_string(i) + " is (" +
                           std::to_string(out.positions[i].x) + ", " + std::to_string(out.positions[i].y) + ", " +
                           std::to_string(out.positions[i].z) + "), not finite");
    const std::size_t vertexCount = out.positions.size();

    // The vertex sequence: indices (checked) or 0..n-1.
    std::vector<std::uint32_t> seq;
    if (prim.indices >= 0) {
        seq = m_reader.readIndices(prim.indices);
        const int type = m_model.accessors[std::size_t(prim.indices)].componentType;
        const std::uint32_t restart = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 0xffu
                                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 0xffffu
                                                                                       : 0xffffffffu;
        for (std::size_t i = 0; i < seq.size(); ++i) {
            if (seq[i] == restart)
                m_context.fail(m_validator.describeAccessor(prim.indices) + ": index " + std::to_string(i) +
                               " is the primitive-restart value " + std::to_string(restart) +
                               ", which glTF does not allow");
            if (seq[i] >= vertexCount)
                m_context.fail(m_validator.describeAccessor(prim.indices) + ": index " + std::to_string(i) + " is " +
                               std::to_string(seq[i]) + ", but the primitive has only " +
                               std::to_string(vertexCount) + " vertices");
        }
    } else {
        if (vertexCount > std::numeric_limits<std::uint32_t>::max())
            m_context.fail(where + " has more vertices than mvcl supports");
        seq.resize(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i) seq[i] = std::uint32_t(i);
    }

    // Triangulate. glTF 2.0 §3.7.2.1 defines strip triangle i as (v_i, v_{i+1+i%2}, v_{i+2-i%2})
    // and fan triangle i as (v_{i+1}, v_{i+2}, v_0); both keep the strip's/fan's winding.
    std::vector<glm::uvec3> tris;
    const std::size_t n = seq.size();
    if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0)
            m_context.warn(where + ": " + std::to_string(n) + " indices is not a multiple of 3; the last " +
                           std::to_string(n % 3) + " are ignored");
        tris.reserve(n / 3);
        for (std::size_t i = 0; i + 2 < n; i += 3) tris.emplace_back(seq[i], seq[i + 1], seq[i + 2]);
    } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 0; i + 2 < n; ++i) {
            const std::size_t odd = i % 2;
            tris.emplace_back(seq[i], seq[i + 1 + odd], seq[i + 2 - odd]);
        }
    } else {
        for (std::size_t i = 0; i + 2 < n; ++i) tris.emplace_back(seq[i + 1], seq[i + 2], seq[0]);
    }

    // Drop degenerate triangles (repeated vertex or exactly zero area in double).
    out.triangles.reserve(tris.size());
    for (const glm::uvec3 &t : tris) {
        const glm::dvec3 a(out.positions[t.x]), b(out.positions[t.y]), c(out.positions[t.z]);
        const glm::dvec3 cr = glm::cross(b - a, c - a);
        if (t.x == t.y || t.y == t.z || t.x == t.z || (cr.x == 0.0 && cr.y == 0.0 && cr.z == 0.0))
            ++out.degenerate;
        else
            out.triangles.push_back(t);
    }

    const auto nrm = prim.attributes.find("NORMAL");
    if (nrm != prim.attributes.end()) decodeNormals(nrm->second, out);
    decodeTextureAttributes(prim, where, out);
    out.usable = true;
    return out;
}

void GltfSceneBuilder::decodeTextureAttributes(const tinygltf::Primitive &prim, const std::string &where,
                                               DecodedPrimitive &out) {
    const auto read = [&](const char *semantic, int type, auto &&reader) {
        const auto it = prim.attributes.find(semantic);
        if (it == prim.attributes.end()) return decltype(reader(0)){};
        if (m_model.accessors[std::size_t(it->second)].type != type) {
            m_context.warn(where + ": " + semantic + " has the wrong accessor type; ignored");
            return decltype(reader(0)){};
        }
        return reader(it->second);
    };
    out.texcoords0 = read("TEXCOORD_0", TINYGLTF_TYPE_VEC2, [&](int a) { return m_reader.readVec2(a); });
    out.texcoords1 = read("TEXCOORD_1", TINYGLTF_TYPE_VEC2, [&](int a) { return m_reader.readVec2(a); });
    out.tangents = read("TANGENT", TINYGLTF_TYPE_VEC4, [&](int a) { return m_reader.readVec4(a); });
    for (glm::vec4 &t : out.tangents) {
        const float len = glm::length(glm::vec3(t));
        t = len > 0.f && std::isfinite(len) ? glm::vec4(glm::vec3(t) / len, t.w < 0.f ? -1.f : 1.f)
                                            : glm::vec4(1.f, 0.f, 0.f, 1.f);
    }
    // A normal map needs tangents; glTF says to generate them when the file has none.
    if (!out.tangents.empty() || prim.material < 0) return;
    const tinygltf::NormalTextureInfo &normalMap = m_model.materials[std::size_t(prim.material)].normalTexture;
    if (normalMap.index < 0) return;
    const std::vector<glm::vec2> &uvs = normalMap.texCoord == 1 ? out.texcoords1 : out.texcoords0;
    if (uvs.size() == out.positions.size()) out.tangents = generateTangents(out.positions, out.normals, uvs, out.triangles);
}

std::optional<int> GltfSceneBuilder::extrasLayer(const tinygltf::Value &extras, const std::string &owner) const {
    if (!extras.IsObject() || !extras.Has("layer")) return std::nullopt;
    const tinygltf::Value &v = extras.Get("layer");
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : std::numeric_limits<double>::quiet_NaN();
    if (!(std::floor(d) == d) || d < 0.0 || d >= double(kMaxLayers))
        m_context.fail(owner + ": extras.layer must be an integer in 0.." + std::to_string(kMaxLayers - 1));
    return int(d);
}

void GltfSceneBuilder::assignLayer(TriangleMesh &mesh, int node) {
    const tinygltf::Node &nd = m_model.nodes[std::size_t(node)];
    std::optional<int> layer = extrasLayer(nd.extras, m_context.describeNode(node));
    if (!layer) layer = extrasLayer(m_model.meshes[std::size_t(nd.mesh)].extras, m_context.describeMesh(nd.mesh));
    if (layer) {
        mesh.layer = *layer;
        mesh.layerSource = LayerSource::Extras;
    } else if (const std::optional<int> rule = m_options.layerRules.match(nd.name, mesh.meshName)) {
        mesh.layer = *rule;
        mesh.layerSource = LayerSource::Rule;
    } else {
        mesh.layer = 0;
        mesh.layerSource = LayerSource::Unassigned;
    }
    m_scene.layers.ensure(mesh.layer);
}

void GltfSceneBuilder::instantiateMesh(int node, const glm::dmat4 &world) {
    const tinygltf::Node &nd = m_model.nodes[std::size_t(node)];
    const tinygltf::Mesh &gm = m_model.meshes[std::size_t(nd.mesh)];
    const glm::dmat3 linear(world);
    const double det = glm::determinant(linear);
    if (det == 0.0) {
        m_context.warn(m_context.describeNode(node) + " has a zero scale; its mesh instance is dropped");
        return;
    }
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
    // A mirroring transform turns counter-clockwise into clockwise: swap two vertices so that
    // "counter-clockwise = front" still agrees with the (inverse-transpose) normals.
    const bool flip = det < 0.0;

    // One TriangleMesh per (node, material, has-normals): primitives that share a material
    // are merged; a mesh never mixes per-vertex normals with none.
    std::map<std::pair<uint32_t, bool>, std::size_t> groups;
    for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
        const DecodedPrimitive &dp = decode(nd.mesh, int(p));
        if (!dp.usable) continue;
        m_context.report().degenerateTrianglesDropped += dp.degenerate;
        if (dp.triangles.empty()) continue;
        m_triangles += dp.triangles.size();
        if (m_triangles > kMaxSceneTriangles)
            m_context.fail("the scene instantiates more than " + std::to_string(kMaxSceneTriangles) +
                           " triangles, more than mvcl loads");
        const int gmat = gm.primitives[p].material;
        const uint32_t material = gmat >= 0 ? uint32_t(gmat) : defaultMaterial();
        const bool hasNormals = !dp.normals.empty();
        auto [it, inserted] = groups.try_emplace({material, hasNormals}, m_pending.size());
        if (inserted) {
            PendingMesh pm;
            pm.mesh.nodeName = nd.name;
            pm.mesh.meshName = gm.name;
            pm.mesh.name = !nd.name.empty() ? nd.name : !gm.name.empty() ? gm.name : "node " + std::to_string(node);
            pm.mesh.material = material;
            pm.mesh.sourceNode = node;
            pm.mesh.sourceMesh = nd.mesh;
            assignLayer(pm.mesh, node);
            m_pending.push_back(std::move(pm));
        }
        PendingMesh &pm = m_pending[it->second];
        if (pm.world.size() + dp.positions.size() > std::numeric_limits<std::uint32_t>::max())
            m_context.fail(m_context.describeNode(node) + " has more vertices than mvcl supports");
        const auto base = std::uint32_t(pm.world.size());
        for (const glm::vec3 &p3 : dp.positions) pm.world.push_back(glm::dvec3(world * glm::dvec4(glm::dvec3(p3), 1.0)));
        for (const glm::vec3 &n3 : dp.normals) {
            const glm::dvec3 wn = normalMatrix * glm::dvec3(n3);
            const double len = glm::length(wn);
            pm.mesh.normals.push_back(len > 0.0 ? toVec3(wn / len) : n3);
        }
        appendAttribute(pm.mesh.texcoords0, dp.texcoords0, base, dp.positions.size());
        appendAttribute(pm.mesh.texcoords1, dp.texcoords1, base, dp.positions.size());
        std::vector<glm::vec4> tangents = dp.tangents;
        for (glm::vec4 &t : tangents) {
            const glm::dvec3 wt = linear * glm::dvec3(glm::vec3(t));
            const double len = glm::length(wt);
            // A mirroring transform flips the handedness of the (normal, tangent, bitangent) frame.
            t = glm::vec4(len > 0.0 ? toVec3(wt / len) : glm::vec3(t), flip ? -t.w : t.w);
        }
        appendAttribute(pm.mesh.tangents, tangents, base, dp.positions.size());
        for (glm::uvec3 t : dp.triangles) {
            t += glm::uvec3(base);
            if (flip) std::swap(t.y, t.z);
            pm.mesh.indices.push_back(t);
        }
    }
}

template <typename T>
void GltfSceneBuilder::appendAttribute(std::vector<T> &mesh, const std::vector<T> &primitive, std::size_t base,
                                       std::size_t count) {
    // Merged primitives that disagree on having the attribute: the missing ones are zeros.
    if (mesh.empty() && primitive.empty()) return;
    mesh.resize(base, T(0.f));
    if (primitive.size() == count)
        mesh.insert(mesh.end(), primitive.begin(), primitive.end());
    else
        mesh.resize(base + count, T(0.f));
}

// ---------------------------------------------------------------------------------------------
// Cameras and lights

void GltfSceneBuilder::addCamera(int node, const glm::dmat4 &world) {
    const tinygltf::Camera &cam = m_model.cameras[std::size_t(m_model.nodes[std::size_t(node)].camera)];
    const std::string where = m_context.describeNode(node) + " camera";
    if (cam.type != "perspective") {
        m_context.warn(where + ": '" + cam.type + "' cameras are not supported; skipped");
        return;
    }
    const double yfov = cam.perspective.yfov;
    if (!(yfov > 0.0) || !(yfov < 3.14159)) {
        m_context.warn(where + ": yfov " + std::to_string(yfov) + " is not in (0, π); skipped");
        return;
    }
    const glm::dmat3 linear(world);
    const glm::dvec3 forward = linear * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 up = linear * glm::dvec3(0.0, 1.0, 0.0);
    if (!(glm::length(forward) > 0.0) || !(glm::length(up) > 0.0)) {
        m_context.warn(where + " has a zero-scale transform; skipped");
        return;
    }
    PendingCamera pc;
    pc.desc.name = !cam.name.empty() ? cam.name : m_model.nodes[std::size_t(node)].name;
    pc.desc.verticalFovDegrees = float(yfov * 180.0 / 3.14159265358979323846);
    pc.eye = glm::dvec3(world[3]);
    pc.forward = glm::normalize(forward);
    pc.up = glm::normalize(up);
    m_cameras.push_back(pc);
}

void GltfSceneBuilder::addLight(int node, const glm::dmat4 &world) {
    const tinygltf::Value &ext = m_model.nodes[std::size_t(node)].extensions.at("KHR_lights_punctual");
    const tinygltf::Light &src = m_model.lights[std::size_t(ext.Get("light").GetNumberAsInt())];
    const std::string where = m_context.describeNode(node) + " light '" + src.name + "'";
    glm::dvec3 color(1.0);
    if (src.color.size() == 3) color = glm::dvec3(src.color[0], src.color[1], src.color[2]);
    const glm::dvec3 intensity = color * src.intensity;
    if (!std::isfinite(intensity.x) || !std::isfinite(intensity.y) || !std::isfinite(intensity.z)) {
        m_context.warn(where + " has a non-finite colour or intensity; skipped");
        return;
    }
    PendingLight pl;
    pl.light.name = src.name;
    pl.light.intensity = toVec3(intensity);
    pl.position = glm::dvec3(world[3]);
    if (src.type == "directional") {
        const glm::dvec3 dir = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
        if (!(glm::length(dir) > 0.0)) {
            m_context.warn(where + " has a zero-scale transform; skipped");
            return;
        }
        pl.light.type = LightType::Directional;
        pl.light.direction = toVec3(glm::normalize(dir));
    } else if (src.type == "point" || src.type == "spot") {
        if (src.type == "spot") m_context.warn(where + ": spot light treated as a point light (no cone)");
        // KHR_lights_punctual point lights are in candela and fall off as 1/r²: D = r².
        pl.light.type = LightType::Point;
        pl.light.constantAttenuation = 0.f;
        pl.light.linearAttenuation = 0.f;
        pl.light.quadraticAttenuation = 1.f;
    } else {
        m_context.warn(where + ": unknown light type '" + src.type + "'; skipped");
        return;
    }
    m_lights.push_back(pl);
}

// ---------------------------------------------------------------------------------------------
// Re-centring

void GltfSceneBuilder::finish() {
    // The world AABB centre becomes the scene-space origin (in double), so that a model placed
    // far from the glTF origin keeps full float precision around itself.
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const PendingMesh &pm : m_pending)
        for (const glm::dvec3 &p : pm.world) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    const glm::dvec3 origin = lo.x <= hi.x ? 0.5 * (lo + hi) : glm::dvec3(0.0);
    m_scene.worldOrigin = origin;

    m_scene.meshes.reserve(m_pending.size());
    for (PendingMesh &pm : m_pending) {
        pm.mesh.positions.resize(pm.world.size());
        for (std::size_t i = 0; i < pm.world.size(); ++i) {
            pm.mesh.positions[i] = toVec3(pm.world[i] - origin);
            if (!isFinite(pm.mesh.positions[i]))
                m_context.fail(m_context.describeNode(pm.mesh.sourceNode) +
                               ": transformed positions exceed the float range");
        }
        pm.world = {};
        m_scene.meshes.push_back(std::move(pm.mesh));
    }
    m_pending.clear();
    recordMeshClosure(m_scene);
    for (const PendingCamera &pc : m_cameras) {
        CameraDesc c = pc.desc;
        c.eye = toVec3(pc.eye - origin);
        c.target = toVec3(pc.eye + pc.forward - origin);
        c.up = toVec3(pc.up);
        m_scene.cameras.push_back(c);
    }
    for (const PendingLight &pl : m_lights) {
        Light l = pl.light;
        l.position = toVec3(pl.position - origin);
        m_scene.lights.push_back(l);
    }
    if (m_scene.materials.empty()) defaultMaterial();
}

} // namespace mvcl::gltf
