#include "GltfFileSandbox_p.h"

#include "GltfText_p.h"

#include <fstream>
#include <system_error>

namespace mvcl::gltf {

namespace fs = std::filesystem;

namespace {
/// URIs come from the file: keep control characters and raw bytes out of error messages.
std::string printable(const std::string &text) { return printableText(text); }

} // namespace

GltfFileSandbox::GltfFileSandbox(const fs::path &baseDir, std::uint64_t maxBytes) : m_remainingBytes(maxBytes) {
    if (!baseDir.empty()) {
        std::error_code ec;
        m_baseDir = fs::weakly_canonical(fs::absolute(baseDir, ec), ec);
        m_hasBaseDir = !ec && !m_baseDir.empty();
    }
}

tinygltf::FsCallbacks GltfFileSandbox::callbacks() {
    tinygltf::FsCallbacks cb{};
    cb.FileExists = &GltfFileSandbox::fileExists;
    cb.ExpandFilePath = &GltfFileSandbox::expandFilePath;
    cb.ReadWholeFile = &GltfFileSandbox::readWholeFile;
    cb.WriteWholeFile = &GltfFileSandbox::writeWholeFile;
    cb.user_data = this;
    return cb;
}

void GltfFileSandbox::refuse(const std::string &uri, const std::string &why) {
    const std::string message = "uri '" + printable(uri) + "' " + why;
    for (const std::string &v : m_violations)
        if (v == message) return; // tinygltf tries each uri twice ("" and "." prefixes)
    m_violations.push_back(message);
}

std::string GltfFileSandbox::resolve(const std::string &uri) {
    if (uri.empty()) return {};
    if (uri.find('\0') != std::string::npos) {
        refuse(uri, "contains a NUL byte");
        return {};
    }
    // tinygltf joins "." + uri on its second attempt; that is the same relative path.
    std::string rel = uri.rfind("./", 0) == 0 ? uri.substr(2) : uri;
    const bool driveLetter = rel.size() >= 2 && rel[1] == ':' &&
                             ((rel[0] >= 'A' && rel[0] <= 'Z') || (rel[0] >= 'a' && rel[0] <= 'z'));
    if (rel.empty() || rel[0] == '/' || rel[0] == '\\' || driveLetter) {
        refuse(uri, "is an absolute path; external files must lie in the asset's folder");
        return {};
    }
    // tinygltf decodes base64 data URIs itself; any other "data:" reaching us is one it could
    // not decode, and would otherwise be reported as a missing file of that name.
    if (rel.rfind("data:", 0) == 0) {
        refuse(uri, "is a data URI tinygltf cannot decode (only base64 application/octet-stream or "
                    "application/gltf-buffer buffers are supported)");
        return {};
    }
    if (rel.find("://") != std::string::npos || rel.rfind("file:", 0) == 0) {
        refuse(uri, "is a URL; only data URIs and relative paths are allowed");
        return {};
    }
    // Reject any ".." component outright (also with Windows separators), even when it would
    // come back into the folder: it is never needed and always suspicious.
    std::size_t start = 0;
    while (start <= rel.size()) {
        std::size_t end = rel.find_first_of("/\\", start);
        if (end == std::string::npos) end = rel.size();
        if (rel.compare(start, end - start, "..") == 0) {
            refuse(uri, "leaves the asset's folder ('..'); external files must lie in it");
            return {};
        }
        start = end + 1;
    }
    if (!m_hasBaseDir) {
        refuse(uri, "refers to an external file, but no asset folder was given");
        return {};
    }
    // Symlinks may still point outside: compare canonical paths element by element.
    std::error_code ec;
    const fs::path full = fs::weakly_canonical(m_baseDir / fs::path(rel), ec);
    if (ec) return {};
    auto b = m_baseDir.begin(), f = full.begin();
    for (; b != m_baseDir.end(); ++b, ++f)
        if (f == full.end() || *b != *f) {
            refuse(uri, "resolves outside the asset's folder");
            return {};
        }
    const std::string out = full.string();
    m_approved.insert(out);
    return out;
}

std::string GltfFileSandbox::expandFilePath(const std::string &uri, void *self) {
    return static_cast<GltfFileSandbox *>(self)->resolve(uri);
}

bool GltfFileSandbox::fileExists(const std::string &path, void *self) {
    auto *sandbox = static_cast<GltfFileSandbox *>(self);
    if (path.empty() || !sandbox->m_approved.count(path)) return false;
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

bool GltfFileSandbox::readWholeFile(std::vector<unsigned char> *out, std::string *err, const std::string &path,
                                    void *self) {
    auto *sandbox = static_cast<GltfFileSandbox *>(self);
    if (!sandbox->m_approved.count(path)) {
        if (err) *err += "not an approved path";
        return false;
    }
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec || !fs::is_regular_file(path, ec)) {
        if (err) *err += "not a readable regular file";
        return false;
    }
    if (size > sandbox->m_remainingBytes) {
        if (err) *err += "external files exceed the size limit";
        sandbox->m_violations.push_back("external file '" + path + "' (" + std::to_string(size) +
                                        " bytes) exceeds the file size limit");
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (err) *err += "cannot open";
        return false;
    }
    out->resize(std::size_t(size));
    if (size > 0 && !in.read(reinterpret_cast<char *>(out->data()), std::streamsize(size))) {
        if (err) *err += "read error";
        return false;
    }
    sandbox->m_remainingBytes -= size;
    return true;
}

bool GltfFileSandbox::writeWholeFile(std::string *err, const std::string &, const std::vector<unsigned char> &,
                                     void *) {
    if (err) *err += "writing is not allowed";
    return false;
}

} // namespace mvcl::gltf
