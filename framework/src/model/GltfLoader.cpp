/// glTF 2.0 loader: tinygltf parses, then our own validation (GltfValidator) and scene building
/// (GltfSceneBuilder). docs/gltf-loading.md describes every check.
///
/// Stages:
///   1. size cap; GLB header and chunk lengths checked here (tinygltf 2.7 can read up to 8 bytes
///      past a truncated BIN chunk); JSON nesting depth capped (tinygltf converts `extras`
///      recursively);
///   2. tinygltf with its image decoders off (encoded bytes kept) and sandboxed file access
///      (GltfFileSandbox);
///   3. GltfValidator: asset version, extensionsRequired, bufferView/accessor bounds in checked
///      uint64, sparse accessors, index accessor types, node forest (no cycles, one parent), scene;
///   4. GltfMaterialBuilder: materials, and the textures they use decoded (GltfImageDecoder);
///   5. GltfSceneBuilder: node transforms in double, one TriangleMesh per (node, material),
///      triangulation, normals, re-centring on the world AABB centre, lights, cameras, layers.
///
/// Materials and textures: GltfMaterialBuilder (the mapping is in PhongTerms.h); images are
/// decoded by GltfImageDecoder.
///
/// Lights (KHR_lights_punctual): intensity = colour · intensity (candela for point/spot, lux for
/// directional); point lights fall off as 1/r² (constant = linear = 0, quadratic = 1); spot lights
/// become point lights (with a warning); directional lights shine along the node's −Z.
/// Cameras: perspective camera nodes → CameraDesc{eye = node origin, target = eye + node −Z,
/// up = node +Y, yfov in degrees}; orthographic cameras are skipped with a warning.
/// Layers: node extras.layer, then mesh extras.layer (LayerSource::Extras), then the options'
/// layer rules on (node name, mesh name) (LayerSource::Rule), else LayerSource::Unassigned.

#include <mvcl/model/GltfLoader.h>

#include "GltfContext_p.h"
#include "GltfFileSandbox_p.h"
#include "GltfJsonPreflight_p.h"
#include "GltfMemoryEstimate_p.h"
#include "GltfMaterialBuilder_p.h"
#include "GltfSceneBuilder_p.h"
#include "GltfText_p.h"
#include "GltfValidator_p.h"

#include <mvcl/core/Error.h>

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>

namespace mvcl {

namespace {

/// Deeper JSON than this is refused before tinygltf sees it (its extras conversion recurses).
constexpr int kMaxJsonDepth = 512;

std::uint32_t readLe32(const std::uint8_t *p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

/// Checks the GLB container so that tinygltf only ever reads inside `bytes`.
/// Returns the JSON chunk.
std::span<const std::uint8_t> checkGlb(std::span<const std::uint8_t> bytes, const std::string &source) {
    if (bytes.size() < 20) throw Error(source, "GLB file is shorter than its 20-byte header");
    const std::uint32_t version = readLe32(bytes.data() + 4);
    const std::uint64_t length = readLe32(bytes.data() + 8);
    const std::uint64_t jsonLength = readLe32(bytes.data() + 12);
    if (version != 2) throw Error(source, "GLB version is " + std::to_string(version) + ", expected 2");
    if (length > bytes.size())
        throw Error(source, "GLB header says " + std::to_string(length) + " bytes, but the file has " +
                                std::to_string(bytes.size()) + " (truncated?)");
    if (readLe32(bytes.data() + 16) != 0x4E4F534Au) throw Error(source, "GLB first chunk is not JSON");
    if (jsonLength == 0 || 20 + jsonLength > length)
        throw Error(source, "GLB JSON chunk length " + std::to_string(jsonLength) + " does not fit in the file");
    // glTF §4.4.3.1: chunks start and end on 4-byte boundaries; the BIN data is read in place.
    if (jsonLength % 4 != 0)
        throw Error(source, "GLB JSON chunk length " + std::to_string(jsonLength) + " is not a multiple of 4");
    const std::uint64_t binStart = 20 + jsonLength;
    if (binStart < length) {
        if (binStart + 8 > length) throw Error(source, "GLB BIN chunk header is truncated");
        const std::uint64_t binLength = readLe32(bytes.data() + binStart);
        if (binStart + 8 + binLength > length)
            throw Error(source, "GLB BIN chunk (" + std::to_string(binLength) + " bytes) runs past the end of the file");
        if (readLe32(bytes.data() + binStart + 4) != 0x004E4942u)
            throw Error(source, "GLB second chunk is not BIN");
        if (binLength % 4 != 0)
            throw Error(source, "GLB BIN chunk length " + std::to_string(binLength) + " is not a multiple of 4");
    }
    return bytes.subspan(20, std::size_t(jsonLength));
}

void checkJsonDepth(std::span<const std::uint8_t> json, const std::string &source) {
    int depth = 0;
    bool inString = false, escaped = false;
    for (std::uint8_t c : json) {
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            if (++depth > kMaxJsonDepth)
                throw Error(source, "JSON is nested more than " + std::to_string(kMaxJsonDepth) + " levels deep");
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
}

/// tinygltf's own decoders stay unused: images given by URI (bytes tinygltf read through the
/// sandbox or decoded from a data URI) are kept encoded for GltfImageDecoder, which decodes only
/// the images materials use, with size limits. Images in a bufferView are read later from the
/// validated buffers (tinygltf passes a pointer it has not bounds-checked: it is not touched).
bool captureImage(tinygltf::Image *image, const int index, std::string *, std::string *, int, int,
                  const unsigned char *bytes, int size, void *user) {
    if (image->bufferView >= 0 || !bytes || size <= 0) return true;
    auto &captured = *static_cast<gltf::CapturedImages *>(user);
    captured[index].assign(bytes, bytes + size);
    return true;
}

/// tinygltf's message on one line, without raw bytes of the file it may quote.
std::string firstLines(const std::string &text) {
    std::string out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
    return gltf::printableText(out, 400);
}

/// The file with its JSON replaced: the text itself for .gltf; for GLB a new header and JSON
/// chunk in front of the original BIN chunk (checkGlb has checked the layout).
std::vector<std::uint8_t> withJson(std::span<const std::uint8_t> original, bool isGlb, std::string json) {
    if (!isGlb) return std::vector<std::uint8_t>(json.begin(), json.end());
    while (json.size() % 4) json += ' ';
    const std::uint64_t oldLength = readLe32(original.data() + 8);
    const std::uint64_t binStart = 20 + std::uint64_t(readLe32(original.data() + 12));
    const std::uint64_t binBytes = oldLength > binStart ? oldLength - binStart : 0;
    std::vector<std::uint8_t> out;
    const auto put32 = [&](std::uint64_t v) {
        for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
    };
    put32(0x46546C67u);
    put32(2);
    put32(12 + 8 + json.size() + binBytes);
    put32(json.size());
    put32(0x4E4F534Au);
    out.insert(out.end(), json.begin(), json.end());
    out.insert(out.end(), original.begin() + std::ptrdiff_t(binStart), original.begin() + std::ptrdiff_t(binStart + binBytes));
    return out;
}

} // namespace

Scene loadGltf(const std::filesystem::path &path, const GltfLoadOptions &options) {
    const std::string source = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(source, "file not found");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(source, "not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error(source, "cannot read the file size: " + ec.message());
    if (size > options.maxFileBytes)
        throw Error(source, "file is " + std::to_string(size) + " bytes, more than the limit of " +
                                std::to_string(options.maxFileBytes));
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    std::ifstream in(path, std::ios::binary);
    if (!in || (size > 0 && !in.read(reinterpret_cast<char *>(bytes.data()), std::streamsize(size))))
        throw Error(source, "cannot read the file");
    std::filesystem::path baseDir = path.parent_path();
    if (baseDir.empty()) baseDir = ".";
    return loadGltfFromMemory(bytes, source, baseDir, options);
}

Scene loadGltfFromMemory(std::span<const std::uint8_t> bytes, const std::string &name,
                         const std::filesystem::path &baseDir, const GltfLoadOptions &options) {
    if (bytes.size() > options.maxFileBytes)
        throw Error(name, "file is " + std::to_string(bytes.size()) + " bytes, more than the limit of " +
                              std::to_string(options.maxFileBytes));
    if (bytes.size() >= std::numeric_limits<unsigned int>::max())
        throw Error(name, "file is 4 GiB or larger, which tinygltf cannot read");
    if (bytes.empty()) throw Error(name, "file is empty");

    const bool isGlb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    const std::span<const std::uint8_t> json = isGlb ? checkGlb(bytes, name) : bytes;
    checkJsonDepth(json, name);
    // Our own read of the JSON first: names unsupported required extensions, repairs what the
    // glTF-Validator accepts and tinygltf does not, and offers fallbacks if tinygltf refuses.
    gltf::GltfJsonPreflight preflight(json, isGlb, name);

    try {
        std::vector<std::string> repairs = preflight.warnings();
        std::vector<std::uint8_t> rebuilt;
        std::span<const std::uint8_t> input = bytes;
        if (preflight.repaired()) {
            rebuilt = withJson(bytes, isGlb, *preflight.repaired());
            input = rebuilt;
        }
        tinygltf::Model model;
        gltf::CapturedImages images;
        std::string err, warn, firstError;
        for (;;) {
            tinygltf::TinyGLTF parser;
            gltf::GltfFileSandbox sandbox(baseDir, options.maxFileBytes);
            model = tinygltf::Model();
            images.clear();
            err.clear();
            warn.clear();
            parser.SetImageLoader(&captureImage, &images);
            parser.SetFsCallbacks(sandbox.callbacks());
            // base_dir "": the sandbox sees each URI as written and resolves it against baseDir itself.
            const bool ok = isGlb ? parser.LoadBinaryFromMemory(&model, &err, &warn, input.data(),
                                                                static_cast<unsigned int>(input.size()), "")
                                  : parser.LoadASCIIFromString(&model, &err, &warn,
                                                               reinterpret_cast<const char *>(input.data()),
                                                               static_cast<unsigned int>(input.size()), "");
            if (!sandbox.violations().empty()) throw Error(name, sandbox.violations().front());
            if (ok) break;
            const std::string detail = firstLines(err);
            if (firstError.empty()) firstError = detail.empty() ? std::string("tinygltf failed") : detail;
            // Try again without the parts mvcl does not render; the geometry is what matters.
            auto fallback = preflight.nextFallback();
            if (!fallback) throw Error(name, "not a valid glTF file: " + firstError);
            repairs.push_back("tinygltf refused the file (" + firstError + "); loaded without its " + fallback->second);
            rebuilt = withJson(bytes, isGlb, std::move(fallback->first));
            input = rebuilt;
        }

        Scene scene;
        scene.name = name;
        scene.report.warnings = repairs;
        std::istringstream warnings(warn + "\n" + err); // err may hold non-fatal notes on success
        for (std::string line; std::getline(warnings, line);)
            if (!line.empty()) scene.report.warnings.push_back("tinygltf: " + gltf::printableText(line, 400));

        gltf::GltfContext context(model, name, scene.report);
        gltf::GltfValidator validator(context);
        validator.validate();
        if (options.maxGeometryBytes > 0) detail::refuseOverBudget(gltf::estimateGeometryMemory(context, validator), options.maxGeometryBytes);
        gltf::GltfMaterialBuilder materials(context, images, options, scene);
        materials.build();
        gltf::GltfSceneBuilder builder(context, validator, options, scene);
        builder.build();
        return scene;
    } catch (const Error &e) {
        if (e.source().empty()) throw Error(name, e.problem());
        throw;
    } catch (const std::bad_alloc &) {
        throw Error(name, "out of memory while loading");
    } catch (const std::exception &e) {
        throw Error(name, std::string("glTF parse error: ") + e.what());
    }
}

} // namespace mvcl
