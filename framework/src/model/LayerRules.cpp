#include <mvcl/model/LayerRules.h>

#include <mvcl/core/Error.h>
#include <mvcl/model/LayerTable.h>

#include <nlohmann/json.hpp>

#include <charconv>
#include <fstream>
#include <sstream>

namespace mvcl {

// Iterative glob with single-star backtracking: on a mismatch we only ever return to the most
// recent '*' and let it swallow one more character. Earlier stars never need revisiting (any
// run they could absorb, the later star can absorb too), so this is O(|pattern|·|text|) in the
// worst case instead of the exponential time of the naive recursive matcher.
bool globMatch(std::string_view pattern, std::string_view text) {
    std::size_t p = 0, t = 0;
    std::size_t starP = std::string_view::npos, starT = 0;
    while (t < text.size()) {
        if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
            ++p;
            ++t;
        } else if (p < pattern.size() && pattern[p] == '*') {
            starP = p++;
            starT = t;
        } else if (starP != std::string_view::npos) {
            p = starP + 1;
            t = ++starT;
        } else {
            return false;
        }
    }
    while (p < pattern.size() && pattern[p] == '*') ++p;
    return p == pattern.size();
}

void LayerRules::add(LayerRule rule) {
    if (rule.layer < 0 || rule.layer >= kMaxLayers)
        throw Error("", "layer rule '" + rule.pattern + "': layer " + std::to_string(rule.layer) +
                            " is out of range 0.." + std::to_string(kMaxLayers - 1));
    m_rules.push_back(std::move(rule));
}

std::optional<int> LayerRules::match(std::string_view nodeName, std::string_view meshName) const {
    // Rule order decides (first matching rule wins); within a rule the node name is tried first.
    for (const LayerRule &rule : m_rules) {
        if (!nodeName.empty() && globMatch(rule.pattern, nodeName)) return rule.layer;
        if (!meshName.empty() && globMatch(rule.pattern, meshName)) return rule.layer;
    }
    return std::nullopt;
}

void LayerRules::nameLayers(LayerTable &layers) const {
    for (auto it = m_rules.rbegin(); it != m_rules.rend(); ++it) // backwards: the first rule is applied last
        if (!it->name.empty() && layers.find(it->layer)) layers.ensure(it->layer).name = it->name;
}

namespace {

std::string_view trim(std::string_view s) {
    const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
    while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
    return s;
}

} // namespace

LayerRules LayerRules::fromString(std::string_view text) {
    LayerRules rules;
    const std::string source = "layer rules";
    std::size_t start = 0;
    int index = 0;
    while (start <= text.size()) {
        std::size_t end = text.find(';', start);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view item = trim(text.substr(start, end - start));
        start = end + 1;
        ++index;
        if (item.empty()) continue; // tolerate "a=0;" and ";;"
        // Split at the last '=' so patterns may not contain '=', but layer numbers never do.
        const std::size_t eq = item.rfind('=');
        if (eq == std::string_view::npos)
            throw Error(source, "rule " + std::to_string(index) + " '" + std::string(item) +
                                    "' has no '=' (expected glob=layer)");
        const std::string_view pattern = trim(item.substr(0, eq));
        std::string_view number = trim(item.substr(eq + 1));
        std::string_view name;
        if (const std::size_t colon = number.find(':'); colon != std::string_view::npos) {
            name = trim(number.substr(colon + 1));
            number = trim(number.substr(0, colon));
        }
        if (pattern.empty())
            throw Error(source, "rule " + std::to_string(index) + " '" + std::string(item) +
                                    "' has an empty pattern");
        int layer = -1;
        const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), layer);
        if (number.empty() || ec != std::errc() || ptr != number.data() + number.size())
            throw Error(source, "rule " + std::to_string(index) + " '" + std::string(item) +
                                    "': layer '" + std::string(number) + "' is not an integer");
        if (layer < 0 || layer >= kMaxLayers)
            throw Error(source, "rule " + std::to_string(index) + " '" + std::string(item) +
                                    "': layer " + std::to_string(layer) + " is out of range 0.." +
                                    std::to_string(kMaxLayers - 1));
        rules.add({std::string(pattern), layer, std::string(name)});
    }
    return rules;
}

LayerRules LayerRules::fromJsonFile(const std::filesystem::path &path) {
    const std::string source = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(source, "cannot open the layer rules file");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return fromJsonText(buffer.str(), source);
}

LayerRules LayerRules::fromJsonText(std::string_view text, const std::string &source) {
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception &e) {
        throw Error(source, std::string("invalid JSON: ") + e.what());
    }
    if (!doc.is_object()) throw Error(source, "the top level must be an object {\"rules\": [...]}");
    for (const auto &[key, value] : doc.items())
        if (key != "rules") throw Error(source, "unknown key '" + key + "' (expected only \"rules\")");
    const auto it = doc.find("rules");
    if (it == doc.end()) throw Error(source, "missing \"rules\" array");
    if (!it->is_array()) throw Error(source, "\"rules\" must be an array");

    LayerRules rules;
    for (std::size_t i = 0; i < it->size(); ++i) {
        const nlohmann::json &r = (*it)[i];
        const std::string where = "rule " + std::to_string(i);
        if (!r.is_object()) throw Error(source, where + " must be an object {\"match\":…, \"layer\":…}");
        for (const auto &[key, value] : r.items())
            if (key != "match" && key != "layer" && key != "name")
                throw Error(source, where + ": unknown key '" + key + "' (expected match, layer, name)");
        const auto m = r.find("match");
        const auto l = r.find("layer");
        if (m == r.end() || !m->is_string() || m->get<std::string>().empty())
            throw Error(source, where + ": \"match\" must be a non-empty string");
        if (l == r.end() || !l->is_number_integer())
            throw Error(source, where + ": \"layer\" must be an integer");
        const auto layer = l->get<long long>();
        if (layer < 0 || layer >= kMaxLayers)
            throw Error(source, where + ": layer " + std::to_string(layer) + " is out of range 0.." +
                                    std::to_string(kMaxLayers - 1));
        const auto n = r.find("name");
        if (n != r.end() && !n->is_string()) throw Error(source, where + ": \"name\" must be a string");
        rules.add({m->get<std::string>(), int(layer), n != r.end() ? n->get<std::string>() : std::string()});
    }
    return rules;
}

} // namespace mvcl
