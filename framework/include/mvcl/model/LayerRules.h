#pragma once
/// \file LayerRules.h
/// User rules "name glob → layer", e.g. `*skin*=0`, `*spongy*=2`. The first matching rule wins.
/// A rule may also name its layer: `*skin*=0:skin`.
/// From a JSON file: {"rules": [{"match": "*skin*", "layer": 0, "name": "skin"}, ...]}
/// or from a CLI string: "*skin*=0:skin;*bone*=1".

#include <mvcl/core/Export.h>

#include <mvcl/model/LayerTable.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mvcl {

struct LayerRule {
    LayerRule() = default;
    /// A constructor rather than an aggregate, so that `{pattern, layer}` needs no name.
    LayerRule(std::string pattern, int layer, std::string name = {})
        : pattern(std::move(pattern)), layer(layer), name(std::move(name)) {}

    std::string pattern; ///< glob: `*` any run, `?` one character; case-sensitive
    int layer = 0;
    /// The name the rule gives its layer; empty = the rule names nothing.
    std::string name;
};

class MVCL_EXPORT LayerRules {
public:
    void add(LayerRule rule);
    const std::vector<LayerRule> &rules() const { return m_rules; }
    bool isEmpty() const { return m_rules.empty(); }

    /// Layer of the first rule matching any of the names (node name, then mesh name).
    std::optional<int> match(std::string_view nodeName, std::string_view meshName) const;

    /// Throws mvcl::Error naming the file and the problem.
    static LayerRules fromJsonFile(const std::filesystem::path &path);
    /// The same format from text already read; errors name `sourceName`.
    static LayerRules fromJsonText(std::string_view text, const std::string &sourceName);
    /// Parses "glob=layer;glob=layer". Throws mvcl::Error on bad syntax or a layer out of range.
    static LayerRules fromString(std::string_view text);

    /// Gives every layer of `layers` that a rule with a name assigns that name (the first such
    /// rule for a layer wins, as for matching).
    void nameLayers(LayerTable &layers) const;

private:
    std::vector<LayerRule> m_rules;
};

/// Glob match with `*` and `?`.
MVCL_EXPORT bool globMatch(std::string_view pattern, std::string_view text);

} // namespace mvcl
