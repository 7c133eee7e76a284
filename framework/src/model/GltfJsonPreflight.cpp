#include "GltfJsonPreflight_p.h"

#include "GltfText_p.h"
#include "GltfValidator_p.h"

#include <mvcl/core/Error.h>

#include <set>

namespace mvcl::gltf {

namespace {

/// Buffers larger than this that nothing reads and that have no uri are refused rather than
/// zero-filled (a tiny file must not allocate gigabytes).
constexpr std::uint64_t kMaxZeroFilledBuffer = 1u << 24;

/// The data URI prefixes tinygltf decodes.
bool tinygltfDecodes(const std::string &uri) {
    for (const char *p : {"data:application/octet-stream;base64,", "data:image/jpeg;base64,", "data:image/png;base64,",
                          "data:image/bmp;base64,", "data:image/gif;base64,", "data:text/plain;base64,",
                          "data:application/gltf-buffer;base64,"})
        if (uri.rfind(p, 0) == 0) return true;
    return false;
}

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

std::string base64(const std::string &data) {
    static const char *kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    const auto byte = [&](std::size_t k) { return std::uint32_t(static_cast<unsigned char>(data[k])); };
    for (; i + 2 < data.size(); i += 3) {
        const std::uint32_t v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
        for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
    }
    if (i + 1 == data.size()) {
        const std::uint32_t v = byte(i) << 16;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == data.size()) {
        const std::uint32_t v = byte(i) << 16 | byte(i + 1) << 8;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

/// A data URI tinygltf cannot decode, rewritten as one it can; nullopt when it is not a data URI
/// we understand (then tinygltf and the sandbox report it).
std::optional<std::string> rewriteDataUri(const std::string &uri, const char *mediaType, std::size_t &decodedBytes) {
    if (uri.rfind("data:", 0) != 0 || tinygltfDecodes(uri)) return std::nullopt;
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos) return std::nullopt;
    const std::string header = uri.substr(5, comma - 5);
    const std::string payload = uri.substr(comma + 1);
    if (header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0) {
        decodedBytes = payload.size() / 4 * 3; // about: tinygltf checks the exact length
        return std::string("data:") + mediaType + ";base64," + payload; // only the media type differs
    }
    // RFC 2397 without ;base64: the data is percent-encoded.
    std::string bytes;
    bytes.reserve(payload.size());
    for (std::size_t i = 0; i < payload.size(); ++i) {
        if (payload[i] == '%') {
            const int hi = i + 1 < payload.size() ? hexValue(payload[i + 1]) : -1;
            const int lo = i + 2 < payload.size() ? hexValue(payload[i + 2]) : -1;
            if (hi < 0 || lo < 0) return std::nullopt;
            bytes += char(hi * 16 + lo);
            i += 2;
        } else {
            bytes += payload[i];
        }
    }
    decodedBytes = bytes.size();
    return std::string("data:") + mediaType + ";base64," + base64(bytes);
}

} // namespace

GltfJsonPreflight::GltfJsonPreflight(std::span<const std::uint8_t> json, bool isGlb, const std::string &source)
    : m_isGlb(isGlb), m_source(source) {
    // Invalid JSON is tinygltf's to report; the preflight then changes nothing.
    m_doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
    m_parsed = !m_doc.is_discarded() && m_doc.is_object();
    if (!m_parsed) return;
    checkRequiredExtensions(source);
    const std::string before = m_doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    repairVersion();
    repairDataUris();
    repairBuffersWithoutUri(source);
    repairMaterialTypes();
    repairNames();
    if (!m_warnings.empty()) {
        std::string after = m_doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        if (after != before) m_repaired = std::move(after);
    }
}

void GltfJsonPreflight::checkRequiredExtensions(const std::string &source) const {
    const auto it = m_doc.find("extensionsRequired");
    if (it == m_doc.end() || !it->is_array()) return;
    std::string missing;
    for (const nlohmann::json &ext : *it)
        if (ext.is_string() && !GltfValidator::isSupportedRequiredExtension(ext.get<std::string>()))
            missing += (missing.empty() ? "" : ", ") + ext.get<std::string>();
    if (!missing.empty())
        throw Error(source, "the file requires extension " + missing + ", which mvcl does not support");
}

void GltfJsonPreflight::repairVersion() {
    const auto asset = m_doc.find("asset");
    if (asset == m_doc.end() || !asset->is_object()) return;
    const auto version = asset->find("version"), minVersion = asset->find("minVersion");
    if (version == asset->end() || minVersion == asset->end() || !version->is_string() || !minVersion->is_string())
        return;
    // minVersion above version contradicts the file's own version, which says what it needs.
    const std::string v = version->get<std::string>(), mv = minVersion->get<std::string>();
    if (v == "2.0" && mv != "2.0") {
        m_warnings.push_back("asset.minVersion '" + mv.substr(0, 20) + "' is above asset.version 2.0; read as 2.0");
        asset->erase("minVersion");
    }
}

void GltfJsonPreflight::repairDataUris() {
    const auto repair = [&](const char *array, const char *what) {
        const auto it = m_doc.find(array);
        if (it == m_doc.end() || !it->is_array()) return;
        for (std::size_t i = 0; i < it->size(); ++i) {
            nlohmann::json &item = (*it)[i];
            if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
            const std::string uri = item["uri"].get<std::string>();
            const bool isImage = std::string(array) == "images";
            const char *media = !isImage ? "application/octet-stream"
                                : uri.rfind("data:image/png", 0) == 0 ? "image/png"
                                : uri.rfind("data:image/jpeg", 0) == 0 ? "image/jpeg"
                                                                        : "application/octet-stream";
            std::size_t decoded = 0;
            if (const std::optional<std::string> fixed = rewriteDataUri(uri, media, decoded)) {
                if (!isImage && item.contains("byteLength") && item["byteLength"].is_number_unsigned() &&
                    decoded < item["byteLength"].get<std::uint64_t>() && uri.find(";base64,") == std::string::npos)
                    throw Error(m_source, std::string(what) + " " + std::to_string(i) + ": its percent-encoded data URI holds " +
                                              std::to_string(decoded) + " bytes, fewer than its byteLength " +
                                              std::to_string(item["byteLength"].get<std::uint64_t>()));
                item["uri"] = *fixed;
                m_warnings.push_back(std::string(what) + " " + std::to_string(i) +
                                     ": data URI re-encoded as base64 (it was percent-encoded or of another media type)");
            }
        }
    };
    repair("buffers", "buffer");
    repair("images", "image");
}

void GltfJsonPreflight::repairBuffersWithoutUri(const std::string &source) {
    const auto buffers = m_doc.find("buffers");
    if (buffers == m_doc.end() || !buffers->is_array()) return;
    std::set<std::size_t> used;
    if (const auto views = m_doc.find("bufferViews"); views != m_doc.end() && views->is_array())
        for (const nlohmann::json &v : *views)
            if (v.is_object() && v.contains("buffer") && v["buffer"].is_number_unsigned())
                used.insert(v["buffer"].get<std::size_t>());
    for (std::size_t i = 0; i < buffers->size(); ++i) {
        nlohmann::json &b = (*buffers)[i];
        if (!b.is_object() || b.contains("uri") || (m_isGlb && i == 0)) continue;
        const std::string name = "buffer " + std::to_string(i);
        if (used.count(i))
            throw Error(source, name + " has no uri, but bufferViews read it (only the first buffer of a .glb may "
                                       "omit its uri: it is the BIN chunk)");
        const std::uint64_t length = b.contains("byteLength") && b["byteLength"].is_number_unsigned()
                                         ? b["byteLength"].get<std::uint64_t>()
                                         : 0;
        if (length > kMaxZeroFilledBuffer)
            throw Error(source, name + " has no uri and " + std::to_string(length) + " bytes");
        b["uri"] = "data:application/octet-stream;base64," + base64(std::string(std::size_t(length), '\0'));
        m_warnings.push_back(name + " has no uri and nothing reads it; ignored");
    }
}

void GltfJsonPreflight::repairMaterialTypes() {
    const auto materials = m_doc.find("materials");
    if (materials == m_doc.end() || !materials->is_array()) return;
    for (std::size_t i = 0; i < materials->size(); ++i) {
        nlohmann::json &m = (*materials)[i];
        if (!m.is_object()) continue; // tinygltf refuses it; the fallback replaces materials
        std::string where = "material " + std::to_string(i);
        if (m.contains("name") && m["name"].is_string()) where += " '" + printableText(m["name"].get<std::string>(), 60) + "'";
        // A texture reference must be an object with a non-negative integer index; its
        // extensions objects. tinygltf drops such mistakes silently; we say so.
        const auto checkTextureInfo = [&](nlohmann::json &owner, const char *slot, const char *number) {
            if (!owner.contains(slot)) return;
            nlohmann::json &info = owner[slot];
            const std::string what = where + " " + slot;
            if (!info.is_object()) {
                m_warnings.push_back(what + " is not an object; ignored");
                owner.erase(slot);
                return;
            }
            if (!info.contains("index") || !info["index"].is_number_integer() || info["index"].get<std::int64_t>() < 0) {
                m_warnings.push_back(what + " has no valid texture index; ignored");
                owner.erase(slot);
                return;
            }
            if (number && info.contains(number) && !info[number].is_number()) {
                m_warnings.push_back(what + "." + number + " is not a number; 1 is used");
                info.erase(number);
            }
            if (info.contains("extensions")) {
                nlohmann::json &ext = info["extensions"];
                if (!ext.is_object()) {
                    m_warnings.push_back(what + ".extensions is not an object; ignored");
                    info.erase("extensions");
                } else {
                    for (auto it = ext.begin(); it != ext.end();) {
                        if (!it->is_object()) {
                            m_warnings.push_back(what + " extension " + printableText(it.key(), 60) +
                                                 " is not an object; ignored");
                            it = ext.erase(it);
                        } else {
                            ++it;
                        }
                    }
                }
            }
        };
        if (m.contains("pbrMetallicRoughness")) {
            nlohmann::json &pbr = m["pbrMetallicRoughness"];
            if (!pbr.is_object()) {
                m_warnings.push_back(where + " pbrMetallicRoughness is not an object; glTF's defaults are used");
                m.erase("pbrMetallicRoughness");
            } else {
                checkTextureInfo(pbr, "baseColorTexture", nullptr);
                checkTextureInfo(pbr, "metallicRoughnessTexture", nullptr);
            }
        }
        checkTextureInfo(m, "normalTexture", "scale");
        checkTextureInfo(m, "occlusionTexture", "strength");
        checkTextureInfo(m, "emissiveTexture", nullptr);
    }
}

void GltfJsonPreflight::repairNames() {
    // Names are for display only: one that is not a string is dropped.
    for (const char *array : {"scenes", "nodes", "meshes", "materials", "cameras", "textures", "images"}) {
        const auto it = m_doc.find(array);
        if (it == m_doc.end() || !it->is_array()) continue;
        for (std::size_t i = 0; i < it->size(); ++i) {
            nlohmann::json &item = (*it)[i];
            if (item.is_object() && item.contains("name") && !item["name"].is_string()) {
                std::string kind = array;
                kind.pop_back(); // "scenes" → "scene"
                m_warnings.push_back(kind + " " + std::to_string(i) + " name is not a string; ignored");
                item.erase("name");
            }
        }
    }
}

std::optional<std::pair<std::string, std::string>> GltfJsonPreflight::nextFallback() {
    if (!m_parsed) return std::nullopt;
    // Parts mvcl does not render, in the order they are least missed.
    while (m_fallbackStage < 4) {
        const int stage = m_fallbackStage++;
        std::string dropped;
        if (stage == 0) {
            for (const char *part : {"animations", "skins"})
                if (m_doc.erase(part)) dropped += std::string(dropped.empty() ? "" : " and ") + part;
            if (m_doc.contains("nodes") && m_doc["nodes"].is_array())
                for (nlohmann::json &n : m_doc["nodes"])
                    if (n.is_object()) {
                        n.erase("skin");
                        n.erase("weights");
                    }
        } else if (stage == 1) {
            if (m_doc.erase("cameras")) dropped = "cameras";
            if (m_doc.contains("nodes") && m_doc["nodes"].is_array())
                for (nlohmann::json &n : m_doc["nodes"])
                    if (n.is_object()) n.erase("camera");
        } else if (stage == 2) {
            for (const char *part : {"textures", "images", "samplers"})
                if (m_doc.erase(part)) dropped += std::string(dropped.empty() ? "" : ", ") + part;
            // Materials that named textures would now point at nothing: keep their factors.
            if (!dropped.empty() && m_doc.contains("materials") && m_doc["materials"].is_array())
                for (nlohmann::json &m : m_doc["materials"])
                    if (m.is_object()) {
                        for (const char *slot : {"normalTexture", "occlusionTexture", "emissiveTexture"}) m.erase(slot);
                        if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object())
                            for (const char *slot : {"baseColorTexture", "metallicRoughnessTexture"})
                                m["pbrMetallicRoughness"].erase(slot);
                    }
        } else {
            // Every material becomes glTF's default, keeping the indices primitives refer to.
            if (m_doc.contains("materials") && m_doc["materials"].is_array() && !m_doc["materials"].empty()) {
                for (nlohmann::json &m : m_doc["materials"]) m = nlohmann::json::object();
                dropped = "materials (glTF's default material used)";
            }
        }
        if (!dropped.empty()) return std::make_pair(m_doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), dropped);
    }
    return std::nullopt;
}

} // namespace mvcl::gltf
