#pragma once
/// \file GltfFileSandbox_p.h
/// Private to the glTF loader: the only file access tinygltf gets. External URIs are resolved
/// relative to the asset's folder; absolute paths, URLs, `..` and symlinks leading outside the
/// folder are refused (and remembered, so the loader can say why). Nothing is ever written, and
/// no shell expansion happens (tinygltf's default ExpandFilePath calls wordexp()).

#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace mvcl::gltf {

class GltfFileSandbox {
public:
    /// \param baseDir the asset's folder; empty = no external files at all
    /// \param maxBytes total bytes all external files together may have
    GltfFileSandbox(const std::filesystem::path &baseDir, std::uint64_t maxBytes);

    tinygltf::FsCallbacks callbacks();
    /// Why URIs were refused, in order.
    const std::vector<std::string> &violations() const { return m_violations; }

private:
    static bool fileExists(const std::string &path, void *self);
    static std::string expandFilePath(const std::string &uri, void *self);
    static bool readWholeFile(std::vector<unsigned char> *out, std::string *err, const std::string &path,
                              void *self);
    static bool writeWholeFile(std::string *err, const std::string &path, const std::vector<unsigned char> &data,
                               void *self);

    /// Absolute path of `uri` inside the folder, or "" (and a recorded violation).
    std::string resolve(const std::string &uri);
    void refuse(const std::string &uri, const std::string &why);

    std::filesystem::path m_baseDir; // canonical
    bool m_hasBaseDir = false;
    std::uint64_t m_remainingBytes;
    std::set<std::string> m_approved;
    std::vector<std::string> m_violations;
};

} // namespace mvcl::gltf
