#include <mvcl/model/MeshFileLoader.h>

#include "MeshFileData_p.h"
#include "MeshFileMemoryEstimate_p.h"

#include <mvcl/model/MeshClosure.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <fstream>
#include <limits>
#include <memory>

namespace mvcl {

namespace {

using meshfile::MeshFileData;
using meshfile::MeshPart;

glm::vec3 toVec3(const glm::dvec3 &v) { return glm::vec3(float(v.x), float(v.y), float(v.z)); }

/// File axes and unit → mvcl's world (y up, metres).
struct Frame {
    UpAxis up = UpAxis::Y;
    double scale = 1.0;
    glm::dvec3 apply(const glm::dvec3 &p) const { return scale * direction(p); }
    /// z-up to y-up is a rotation of −90° about x, so windings and handedness stay as they are.
    glm::dvec3 direction(const glm::dvec3 &v) const { return up == UpAxis::Z ? glm::dvec3(v.x, v.z, -v.y) : v; }
};

Frame frameOf(const MeshFileOptions &options, LoadReport &report) {
    Frame frame;
    frame.up = options.upAxis.value_or(UpAxis::Y);
    const LengthUnit unit = options.unit.value_or(LengthUnit::Metre);
    frame.scale = metresPer(unit);
    if (!options.upAxis) report.assumptions.push_back(std::string(upAxisName(frame.up)) + " up");
    if (!options.unit) report.assumptions.push_back(std::string("unit ") + lengthUnitName(unit));
    return frame;
}

/// Parts → scene: axes and unit, normals, degenerate triangles, layer rules, re-centring in
/// double (as the glTF loader does, so far-away models keep float precision) and closure.
Scene assemble(MeshFileData data, const std::string &name, const std::string &stem, const MeshFileOptions &options) {
    Scene scene;
    scene.name = name;
    scene.report.warnings = std::move(data.warnings);
    const Frame frame = frameOf(options, scene.report);
    scene.materials = std::move(data.materials);
    std::optional<uint32_t> defaultMaterial;
    bool averagedColours = false;
    std::vector<std::vector<glm::dvec3>> world;
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (MeshPart &part : data.parts) {
        TriangleMesh mesh;
        mesh.name = part.name.empty() ? stem : part.name;
        mesh.nodeName = mesh.name;
        if (part.group >= 0) { // one OBJ group in several materials is still one solid (closure, inference)
            mesh.sourceNode = part.group;
            mesh.sourceMesh = 0;
        }
        // In place, without copies: a million-triangle file's parts are tens of megabytes.
        std::vector<glm::dvec3> &points = part.positions;
        for (glm::dvec3 &p : points) {
            p = frame.apply(p);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const auto degenerate = [&points](const glm::uvec3 &t) {
            const glm::dvec3 cr = glm::cross(points[t.y] - points[t.x], points[t.z] - points[t.x]);
            return t.x == t.y || t.y == t.z || t.x == t.z || (cr.x == 0.0 && cr.y == 0.0 && cr.z == 0.0);
        };
        const std::size_t dropped = std::erase_if(part.triangles, degenerate);
        scene.report.degenerateTrianglesDropped += dropped;
        if (part.triangles.empty()) continue;
        mesh.indices = std::move(part.triangles);
        world.push_back(std::move(part.positions));
        if (!part.normals.empty()) {
            mesh.normals.reserve(part.normals.size());
            for (const glm::dvec3 &n : part.normals) {
                const double len = meshfile::isFinite(n) ? glm::length(n) : 0.0;
                if (!(len > 0.0)) break;
                if (std::abs(len - 1.0) > 1e-3) ++scene.report.nonUnitNormalsFixed;
                mesh.normals.push_back(toVec3(frame.direction(n / len)));
            }
            if (mesh.normals.size() != part.normals.size()) {
                scene.report.warnings.push_back("'" + mesh.name + "' has zero or non-finite normals; it is shaded flat");
                mesh.normals.clear();
            }
        }
        if (part.material >= 0) {
            mesh.material = uint32_t(part.material);
        } else if (!part.colors.empty()) {
            // The tracer shades a mesh with one material: vertex colours give it their mean.
            glm::dvec3 sum(0.0);
            for (const glm::vec3 &c : part.colors) sum += glm::dvec3(c);
            Material m;
            m.name = mesh.name + " (vertex colours)";
            m.diffuse = m.ambient = toVec3(sum / double(part.colors.size()));
            mesh.material = uint32_t(scene.materials.size());
            scene.materials.push_back(m);
            averagedColours = true;
        } else {
            if (!defaultMaterial) {
                Material m;
                m.name = "default";
                defaultMaterial = uint32_t(scene.materials.size());
                scene.materials.push_back(m);
            }
            mesh.material = *defaultMaterial;
        }
        if (const std::optional<int> rule = options.layerRules.match(mesh.nodeName, mesh.meshName)) {
            mesh.layer = *rule;
            mesh.layerSource = LayerSource::Rule;
        }
        scene.meshes.push_back(std::move(mesh));
    }
    if (scene.meshes.empty()) throw Error(name, "every triangle of the file is degenerate");
    if (averagedColours)
        scene.report.warnings.push_back("vertex colours are averaged into one colour per mesh");
    const glm::dvec3 origin = 0.5 * (lo + hi);
    scene.worldOrigin = origin;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        std::vector<glm::vec3> &positions = scene.meshes[m].positions;
        positions.resize(world[m].size());
        for (std::size_t i = 0; i < positions.size(); ++i) {
            positions[i] = toVec3(world[m][i] - origin);
            if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
                throw Error(name, "coordinates exceed the float range in metres");
        }
    }
    for (const TriangleMesh &m : scene.meshes) scene.layers.ensure(m.layer);
    recordMeshClosure(scene);
    return scene;
}

Scene read(const meshfile::ReadInput &input, MeshFormat format, const std::string &stem, const MeshFileOptions &options) {
    if (input.bytes.empty()) throw Error(input.name, "the file is empty");
    MeshFileData data;
    switch (format) {
    case MeshFormat::Obj: data = meshfile::readObj(input); break;
    case MeshFormat::Stl: data = meshfile::readStl(input); break;
    case MeshFormat::Ply: data = meshfile::readPly(input); break;
    }
    return assemble(std::move(data), input.name, stem, options);
}

/// Refuses a file whose geometry the memory budget cannot hold (MeshFileMemoryEstimate_p.h).
/// `bytes` is the file's beginning, or all of it when `complete`. True when it could tell.
bool checkMemoryBudget(std::span<const std::uint8_t> bytes, std::uint64_t fileSize, bool complete,
                       MeshFormat format, const MeshFileOptions &options, const std::string &name) {
    if (options.maxGeometryBytes == 0) return true;
    try {
        if (const auto estimate = meshfile::estimateFromHeader(bytes, fileSize, format)) {
            detail::refuseOverBudget(*estimate, options.maxGeometryBytes);
            return true;
        }
        if (!complete) return false;
        detail::refuseOverBudget(meshfile::estimateFromText(bytes, format, options.maxGeometryBytes),
                                 options.maxGeometryBytes);
        return true;
    } catch (const Error &e) {
        throw Error(name, e.problem());
    }
}

} // namespace

Scene loadMeshFile(const std::filesystem::path &path, MeshFormat format, const MeshFileOptions &options) {
    const std::string name = path.string();
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error(name, "cannot read the file (" + ec.message() + ")");
    if (size > options.maxFileBytes)
        throw Error(name, "the file has " + std::to_string(size) + " bytes, more than the limit of " +
                              std::to_string(options.maxFileBytes));
    std::ifstream file(path, std::ios::binary);
    bool budgetChecked = options.maxGeometryBytes == 0;
    if (!budgetChecked) {
        // A binary STL's or a PLY's header says what the file holds: refused before the rest
        // of it is read.
        std::vector<std::uint8_t> head(std::min<std::uintmax_t>(size, meshfile::kHeaderProbeBytes));
        if (!file.read(reinterpret_cast<char *>(head.data()), std::streamsize(head.size())))
            throw Error(name, "cannot read the file");
        budgetChecked = checkMemoryBudget(head, size, head.size() == size, format, options, name);
        file.seekg(0);
    }
    // Not zero-filled first: the read writes every byte (tens of megabytes for a large mesh).
    const std::unique_ptr<std::uint8_t[]> storage(new std::uint8_t[size]);
    const std::span<const std::uint8_t> bytes(storage.get(), size);
    if (!file.read(reinterpret_cast<char *>(storage.get()), std::streamsize(size)))
        throw Error(name, "cannot read the file");
    if (!budgetChecked) checkMemoryBudget(bytes, size, true, format, options, name);
    meshfile::ReadInput input{bytes, name, path.parent_path().empty() ? "." : path.parent_path(),
                              {options.maxTriangles}};
    return read(input, format, path.stem().string(), options);
}

Scene loadMeshFileFromMemory(std::span<const std::uint8_t> bytes, const std::string &name, MeshFormat format,
                             const MeshFileOptions &options) {
    if (bytes.size() > options.maxFileBytes) throw Error(name, "the file is larger than the limit");
    checkMemoryBudget(bytes, bytes.size(), true, format, options, name);
    meshfile::ReadInput input{bytes, name, {}, {options.maxTriangles}};
    return read(input, format, std::filesystem::path(name).stem().string(), options);
}

std::optional<UpAxis> upAxisFromName(std::string_view name) {
    if (name == "y") return UpAxis::Y;
    if (name == "z") return UpAxis::Z;
    return std::nullopt;
}

std::optional<LengthUnit> lengthUnitFromName(std::string_view name) {
    if (name == "mm") return LengthUnit::Millimetre;
    if (name == "cm") return LengthUnit::Centimetre;
    if (name == "m") return LengthUnit::Metre;
    if (name == "in") return LengthUnit::Inch;
    return std::nullopt;
}

const char *upAxisName(UpAxis axis) { return axis == UpAxis::Z ? "z" : "y"; }

const char *lengthUnitName(LengthUnit unit) {
    switch (unit) {
    case LengthUnit::Millimetre: return "mm";
    case LengthUnit::Centimetre: return "cm";
    case LengthUnit::Metre: return "m";
    case LengthUnit::Inch: return "in";
    }
    return "m";
}

double metresPer(LengthUnit unit) {
    switch (unit) {
    case LengthUnit::Millimetre: return 0.001;
    case LengthUnit::Centimetre: return 0.01;
    case LengthUnit::Metre: return 1.0;
    case LengthUnit::Inch: return 0.0254;
    }
    return 1.0;
}

} // namespace mvcl
