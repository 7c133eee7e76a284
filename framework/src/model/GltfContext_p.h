#pragma once
/// \file GltfContext_p.h
/// Private to the glTF loader: what every stage needs to report problems with the file's name.

#include <mvcl/core/Error.h>
#include <mvcl/model/Scene.h>

#include <tiny_gltf.h>

#include <cstddef>
#include <string>

namespace mvcl::gltf {

/// Shared state of one load: the parsed model, the source name for errors and the report that
/// collects warnings. Warnings are capped so a hostile file cannot flood the report.
class GltfContext {
public:
    GltfContext(const tinygltf::Model &model, std::string source, LoadReport &report)
        : m_model(model), m_source(std::move(source)), m_report(report) {}

    const tinygltf::Model &model() const { return m_model; }
    const std::string &source() const { return m_source; }
    LoadReport &report() { return m_report; }

    [[noreturn]] void fail(const std::string &problem) const { throw Error(m_source, problem); }

    void warn(const std::string &message) {
        ++m_warningCount;
        if (m_warningCount <= kMaxWarnings)
            m_report.warnings.push_back(message);
        else if (m_warningCount == kMaxWarnings + 1)
            m_report.warnings.push_back("further warnings suppressed");
    }

    /// "mesh 2 'Cube'" or "mesh 2" when unnamed.
    std::string describeMesh(int index) const {
        std::string s = "mesh " + std::to_string(index);
        if (index >= 0 && std::size_t(index) < m_model.meshes.size() &&
            !m_model.meshes[std::size_t(index)].name.empty())
            s += " '" + m_model.meshes[std::size_t(index)].name + "'";
        return s;
    }
    std::string describeNode(int index) const {
        std::string s = "node " + std::to_string(index);
        if (index >= 0 && std::size_t(index) < m_model.nodes.size() &&
            !m_model.nodes[std::size_t(index)].name.empty())
            s += " '" + m_model.nodes[std::size_t(index)].name + "'";
        return s;
    }

private:
    static constexpr std::size_t kMaxWarnings = 50;
    const tinygltf::Model &m_model;
    std::string m_source;
    LoadReport &m_report;
    std::size_t m_warningCount = 0;
};

} // namespace mvcl::gltf
