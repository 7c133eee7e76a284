#include <mvcl/io/LensStackFile.h>

#include "JsonFile_p.h"
#include "LensStackFile_p.h"

#include <mvcl/io/SessionFile.h>

#include <mvcl/core/Error.h>
#include <mvcl/lens/LensRegistry.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <span>
#include <vector>

namespace mvcl {

namespace {

using namespace detail; // the JSON file helpers

constexpr int kFileVersion = 1;

constexpr std::string_view kRegionKeys[] = {"shape",   "center",  "size",        "points",
                                            "feather", "outline", "outlineColor"};

LensStackCamera readCamera(const Json &value, const JsonLocation &where) {
    expectObject(value, where);
    LensStackCamera camera;
    if (value.contains("name")) {
        static constexpr std::string_view kNamedKeys[] = {"name"};
        rejectUnknownKeys(value, kNamedKeys, where);
        const Json &name = value["name"];
        if (name.is_number_unsigned()) camera.sceneCamera = name.dump();
        else camera.sceneCamera = readString(name, where.key("name"));
        if (camera.sceneCamera.empty()) where.key("name").fail("is empty");
        return camera;
    }
    static constexpr std::string_view kViewKeys[] = {"eye", "target", "up", "fov"};
    rejectUnknownKeys(value, kViewKeys, where);
    for (const char *required : {"eye", "target"})
        if (!value.contains(required))
            where.fail(std::string("missing \"") + required + "\" (or give the scene camera's \"name\")");
    camera.eye = readVector<3>(value["eye"], where.key("eye"));
    camera.target = readVector<3>(value["target"], where.key("target"));
    if (camera.eye == camera.target) where.fail("eye and target are the same point");
    if (value.contains("up")) camera.up = readVector<3>(value["up"], where.key("up"));
    if (camera.up == glm::vec3(0.f)) where.key("up").fail("must not be zero");
    if (value.contains("fov")) camera.verticalFovDegrees = readNumber(value["fov"], where.key("fov"));
    if (!(camera.verticalFovDegrees > 0.f && camera.verticalFovDegrees < 180.f))
        where.key("fov").fail("must be in (0, 180) degrees");
    return camera;
}

LensRegion readRegion(const Json &value, const JsonLocation &where) {
    expectObject(value, where);
    rejectUnknownKeys(value, kRegionKeys, where);
    std::string shape = value.contains("points") ? "polygon" : "rectangle";
    if (value.contains("shape")) shape = readString(value["shape"], where.key("shape"));

    std::vector<glm::vec2> points;
    glm::vec2 center(0.5f), size(0.5f);
    if (shape == "polygon") {
        for (const char *boxKey : {"center", "size"})
            if (value.contains(boxKey)) where.key(boxKey).fail("a polygon region is given by its \"points\" only");
        if (!value.contains("points")) where.fail("a polygon region needs \"points\": [[x, y], ...]");
        const JsonLocation pointsWhere = where.key("points");
        if (!value["points"].is_array()) pointsWhere.fail("expected an array of [x, y] points");
        for (std::size_t i = 0; i < value["points"].size(); ++i)
            points.push_back(readVector<2>(value["points"][i], pointsWhere.index(i)));
    } else if (shape == "rectangle" || shape == "ellipse") {
        if (value.contains("points"))
            where.key("points").fail("only a polygon region has points (shape is " + shape + ")");
        if (value.contains("center")) center = readVector<2>(value["center"], where.key("center"));
        if (value.contains("size")) size = readVector<2>(value["size"], where.key("size"));
    } else {
        where.key("shape").fail("unknown shape '" + shape + "' (known: rectangle, ellipse, polygon)");
    }
    const float feather = value.contains("feather") ? readNumber(value["feather"], where.key("feather")) : 0.f;
    const float outline = value.contains("outline") ? readNumber(value["outline"], where.key("outline")) : 0.f;
    const glm::vec3 outlineColor = value.contains("outlineColor")
                                       ? readVector<3>(value["outlineColor"], where.key("outlineColor"))
                                       : LensRegion().outlineColor();
    try {
        LensRegion region = shape == "polygon"   ? LensRegion::polygon(std::move(points))
                            : shape == "ellipse" ? LensRegion::ellipse(center, size)
                                                 : LensRegion::rectangle(center, size);
        region.setFeather(feather);
        region.setOutlineWidth(outline);
        region.setOutlineColor(outlineColor);
        region.validate();
        return region;
    } catch (const Error &e) {
        where.fail(e.problem());
    }
}

std::string unknownPropertyMessage(const std::string &key, const Lens &lens, bool commandLine) {
    std::string message = detail::unknownPropertyMessage(key, lens);
    if (commandLine) message += "; region keys: " + joined(kRegionKeys) + "; label, enabled";
    return message;
}

std::shared_ptr<Lens> readLens(const Json &value, const LensRegistry &registry, const JsonLocation &where) {
    static constexpr std::string_view kLensKeys[] = {"type", "label", "enabled", "region", "properties"};
    expectObject(value, where);
    rejectUnknownKeys(value, kLensKeys, where);
    if (!value.contains("type")) where.fail("missing \"type\"");
    const std::string type = readString(value["type"], where.key("type"));
    std::shared_ptr<Lens> lens;
    try {
        lens = registry.create(type);
    } catch (const Error &e) {
        where.key("type").fail(e.problem());
    }
    if (value.contains("label")) lens->setLabel(readString(value["label"], where.key("label")));
    if (value.contains("enabled")) lens->setEnabled(readBool(value["enabled"], where.key("enabled")));
    if (value.contains("region")) lens->setRegion(readRegion(value["region"], where.section("region")));
    if (value.contains("properties")) {
        const JsonLocation propertiesWhere = where.section("properties");
        for (const auto &[key, propertyValue] : expectObject(value["properties"], propertiesWhere).items()) {
            if (!findProperty(lens->properties(), key))
                propertiesWhere.fail(unknownPropertyMessage(key, *lens, where.commandLine));
            const JsonLocation keyWhere = propertiesWhere.key(key);
            const std::string text = propertyText(propertyValue, keyWhere);
            try {
                lens->setPropertyText(key, text);
            } catch (const Error &e) {
                keyWhere.fail(e.what()); // names the lens type ("lens 'layer': property ...")
            }
        }
    }
    // A lens whose plugin fails is kept, disabled with its fault(), so that nothing the file
    // says is lost when it is written again; only an invalid region is the file's error.
    try {
        lens->commitOrDisable();
    } catch (const Error &e) {
        where.fail(e.what());
    }
    return lens;
}

/// {"relative": fraction of the scene's size} or {"sceneUnits": distance}, finite and ≥ 0.
LayerContact readLayerContact(const Json &json, const JsonLocation &where) {
    const char *expected = "expected {\"relative\": number} or {\"sceneUnits\": number}";
    if (!json.is_object() || json.size() != 1) where.fail(expected);
    LayerContact contact;
    const auto it = json.begin();
    if (it.key() == "sceneUnits") contact.measure = LayerContact::Measure::SceneUnits;
    else if (it.key() != "relative") where.fail(expected);
    if (!it.value().is_number()) where.key(it.key()).fail("expected a number");
    const double value = it.value().get<double>();
    if (!std::isfinite(value) || value < 0.0) where.key(it.key()).fail("the tolerance must be finite and not negative");
    contact.distance = value;
    return contact;
}

} // namespace

namespace detail {

LensStackDescription readDescription(const Json &document, const LensRegistry &registry,
                                     const JsonLocation &where) {
    static constexpr std::string_view kTopKeys[] = {"version", "scene", "camera", "layerRules", "visibleLayers",
                                                    "layerContact", "memoryBudgetMiB", "layerNames", "lenses"};
    expectObject(document, where);
    rejectUnknownKeys(document, kTopKeys, where);
    expectVersion(document, kFileVersion, where);

    LensStackDescription description;
    if (document.contains("scene")) {
        const Json &scene = document["scene"];
        const JsonLocation sceneWhere = where.key("scene");
        if (scene.is_array()) { // several files as layers, the first outermost
            if (scene.empty()) sceneWhere.fail("expected a model path or a non-empty array of them");
            for (std::size_t i = 0; i < scene.size(); ++i) {
                std::string file = readString(scene[i], sceneWhere.index(i));
                if (i == 0) description.scene = std::move(file);
                else description.moreScenes.push_back(std::move(file));
            }
        } else {
            description.scene = readString(scene, sceneWhere);
        }
    }
    if (document.contains("camera")) description.camera = readCamera(document["camera"], where.key("camera"));
    if (document.contains("layerRules")) {
        const JsonLocation rulesWhere = where.key("layerRules");
        if (!document["layerRules"].is_array()) rulesWhere.fail("expected an array of {\"match\", \"layer\"}");
        // The layer-rule reader checks the rules; it reads {"rules": [...]}.
        try {
            description.layerRules =
                LayerRules::fromJsonText(Json{{"rules", document["layerRules"]}}.dump(), where.source);
        } catch (const Error &e) {
            rulesWhere.fail(e.problem());
        }
    }
    if (document.contains("visibleLayers")) {
        const JsonLocation visibleWhere = where.key("visibleLayers");
        try {
            description.visibleLayers = parseLayerSet(propertyText(document["visibleLayers"], visibleWhere));
        } catch (const Error &e) {
            visibleWhere.fail(e.problem());
        }
    }
    if (document.contains("layerContact"))
        description.layerContact = readLayerContact(document["layerContact"], where.key("layerContact"));
    if (document.contains("memoryBudgetMiB")) {
        const Json &budget = document["memoryBudgetMiB"];
        // Up to 2^40 MiB: the bytes must fit 64 bits.
        if (!budget.is_number_integer() || budget.get<long long>() < 1 || budget.get<long long>() > (1ll << 40))
            where.key("memoryBudgetMiB").fail("expected a whole number of MiB ≥ 1, got " + budget.dump());
        description.memoryBudgetBytes = std::uint64_t(budget.get<long long>()) << 20;
    }
    if (document.contains("layerNames")) {
        const JsonLocation namesWhere = where.key("layerNames");
        const Json &names = document["layerNames"];
        if (!names.is_object()) namesWhere.fail("expected an object of layer number → name, e.g. {\"2\": \"bone\"}");
        for (auto it = names.begin(); it != names.end(); ++it) {
            const JsonLocation nameWhere = namesWhere.key(it.key());
            int layer = -1;
            const auto [end, ec] = std::from_chars(it.key().data(), it.key().data() + it.key().size(), layer);
            if (ec != std::errc() || end != it.key().data() + it.key().size() || layer < 0 || layer >= kMaxLayers)
                nameWhere.fail("a layer number 0.." + std::to_string(kMaxLayers - 1) + " is expected as the key");
            std::string name = readString(it.value(), nameWhere);
            if (name.empty()) nameWhere.fail("a layer name must not be empty");
            description.layerNames[layer] = std::move(name);
        }
    }
    if (document.contains("lenses")) {
        const JsonLocation lensesWhere = where.key("lenses");
        const Json &lenses = document["lenses"];
        if (!lenses.is_array()) lensesWhere.fail("expected an array of lenses (bottom to top)");
        for (std::size_t i = 0; i < lenses.size(); ++i) {
            std::shared_ptr<Lens> lens = readLens(lenses[i], registry, lensesWhere.index(i));
            try {
                description.lenses.add(std::move(lens));
            } catch (const Error &e) {
                lensesWhere.index(i).fail(e.problem());
            }
        }
    }
    return description;
}

} // namespace detail

namespace {

const char *shapeName(LensRegion::Shape shape) {
    switch (shape) {
    case LensRegion::Shape::Rectangle: return "rectangle";
    case LensRegion::Shape::Ellipse: return "ellipse";
    case LensRegion::Shape::Polygon: return "polygon";
    }
    return "rectangle";
}

Json regionJson(const LensRegion &region) {
    Json json;
    json["shape"] = shapeName(region.shape());
    if (region.shape() == LensRegion::Shape::Polygon) {
        Json points = Json::array();
        for (const glm::vec2 &point : region.points()) points.push_back(vectorJson(point));
        json["points"] = std::move(points);
    } else {
        json["center"] = vectorJson(region.center());
        json["size"] = vectorJson(region.size());
    }
    json["feather"] = shortestDouble(region.feather());
    json["outline"] = shortestDouble(region.outlineWidth());
    json["outlineColor"] = vectorJson(region.outlineColor());
    return json;
}

Json lensJson(const Lens &lens) {
    const std::shared_ptr<const LensSnapshot> snapshot = lens.snapshot();
    Json json;
    json["type"] = lens.typeName();
    json["label"] = lens.label();
    json["enabled"] = snapshot->enabled;
    json["region"] = regionJson(snapshot->region);
    Json properties = Json::object();
    const std::vector<PropertyValue> values = lens.committedValues();
    for (std::size_t i = 0; i < values.size(); ++i)
        properties[lens.properties()[i].name] = values[i].toString();
    json["properties"] = std::move(properties);
    return json;
}

} // namespace

namespace detail {

Json descriptionJson(const LensStackDescription &description) {
    Json json;
    json["version"] = kFileVersion;
    if (!description.moreScenes.empty()) {
        Json scenes = Json::array({description.scene});
        for (const std::string &s : description.moreScenes) scenes.push_back(s);
        json["scene"] = std::move(scenes);
    } else if (!description.scene.empty()) {
        json["scene"] = description.scene;
    }
    if (const auto &camera = description.camera) {
        if (!camera->sceneCamera.empty()) {
            json["camera"] = {{"name", camera->sceneCamera}};
        } else {
            json["camera"] = {{"eye", vectorJson(camera->eye)},
                              {"target", vectorJson(camera->target)},
                              {"up", vectorJson(camera->up)},
                              {"fov", shortestDouble(camera->verticalFovDegrees)}};
        }
    }
    if (!description.layerRules.isEmpty()) {
        Json rules = Json::array();
        for (const LayerRule &rule : description.layerRules.rules())
            rules.push_back(rule.name.empty() ? Json{{"match", rule.pattern}, {"layer", rule.layer}}
                                              : Json{{"match", rule.pattern}, {"layer", rule.layer}, {"name", rule.name}});
        json["layerRules"] = std::move(rules);
    }
    if (description.visibleLayers != kAllLayers) json["visibleLayers"] = layerSetToString(description.visibleLayers);
    if (const LayerContact &contact = description.layerContact; contact.isEnabled())
        json["layerContact"] = {{contact.measure == LayerContact::Measure::SceneUnits ? "sceneUnits" : "relative",
                                 contact.distance}};
    if (description.memoryBudgetBytes > 0) json["memoryBudgetMiB"] = std::max<std::uint64_t>(description.memoryBudgetBytes >> 20, 1);
    if (!description.layerNames.empty()) {
        Json names = Json::object();
        for (const auto &[layer, name] : description.layerNames) names[std::to_string(layer)] = name;
        json["layerNames"] = std::move(names);
    }
    Json lenses = Json::array();
    for (const std::shared_ptr<Lens> &lens : description.lenses.lenses()) lenses.push_back(lensJson(*lens));
    json["lenses"] = std::move(lenses);
    return json;
}

} // namespace detail

namespace {

bool sameCommittedLens(const Lens &a, const Lens &b) {
    const std::shared_ptr<const LensSnapshot> snapshotA = a.snapshot(), snapshotB = b.snapshot();
    return a.typeName() == b.typeName() && a.label() == b.label() && snapshotA->enabled == snapshotB->enabled &&
           snapshotA->region == snapshotB->region && a.committedValues() == b.committedValues();
}

/// Splits at commas outside brackets: "center=[0.3,0.5],feather=4" → two items.
std::vector<std::string_view> splitOutsideBrackets(std::string_view text, const JsonLocation &where) {
    std::vector<std::string_view> items;
    int depth = 0;
    std::size_t start = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '[') ++depth;
        else if (text[i] == ']' && --depth < 0) where.fail("']' without '['");
        else if (text[i] == ',' && depth == 0) {
            items.push_back(text.substr(start, i - start));
            start = i + 1;
        }
    }
    if (depth != 0) where.fail("'[' without ']'");
    items.push_back(text.substr(start));
    return items;
}

/// 'text' in single quotes. (Built with append: GCC 12 warns falsely, -Wrestrict, on
/// "'" + std::string.)
std::string singleQuoted(std::string_view text) {
    std::string quoted(1, '\'');
    quoted.append(text).push_back('\'');
    return quoted;
}

std::string_view trimmed(std::string_view text) {
    const auto isSpace = [](char c) { return c == ' ' || c == '\t'; };
    while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
    while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
    return text;
}

/// A command-line value as JSON: numbers, booleans and bracketed arrays as such, anything else
/// (ellipse, 1-, primary) as a string.
Json commandLineJson(std::string_view text) {
    if (Json::accept(text)) return Json::parse(text);
    return Json(std::string(text));
}

} // namespace

namespace detail {

bool isSceneFile(const std::string &scene) { return !scene.empty() && !scene.starts_with("builtin:"); }

void resolveScenePaths(LensStackDescription &description, const std::filesystem::path &file) {
    const auto resolve = [&file](std::string &scene) {
        if (isSceneFile(scene) && std::filesystem::path(scene).is_relative())
            scene = (file.parent_path() / scene).lexically_normal().string();
    };
    resolve(description.scene);
    for (std::string &s : description.moreScenes) resolve(s);
}

void relocateScenePaths(LensStackDescription &description, const std::filesystem::path &file) {
    const std::filesystem::path folder = std::filesystem::absolute(file).parent_path();
    const auto relocate = [&folder](std::string &scene) {
        if (isSceneFile(scene)) scene = std::filesystem::absolute(scene).lexically_proximate(folder).string();
    };
    relocate(description.scene);
    for (std::string &s : description.moreScenes) relocate(s);
}

} // namespace detail

bool operator==(const LensStackDescription &a, const LensStackDescription &b) {
    const auto sameRule = [](const LayerRule &x, const LayerRule &y) {
        return x.pattern == y.pattern && x.layer == y.layer && x.name == y.name;
    };
    const auto sameLens = [](const std::shared_ptr<Lens> &x, const std::shared_ptr<Lens> &y) {
        return sameCommittedLens(*x, *y);
    };
    return a.scene == b.scene && a.moreScenes == b.moreScenes && a.camera == b.camera && a.visibleLayers == b.visibleLayers &&
           a.layerContact == b.layerContact && a.memoryBudgetBytes == b.memoryBudgetBytes && a.layerNames == b.layerNames &&
           std::ranges::equal(a.layerRules.rules(), b.layerRules.rules(), sameRule) &&
           std::ranges::equal(a.lenses.lenses(), b.lenses.lenses(), sameLens);
}

LensStackDescription parseLensStackJson(std::string_view text, const std::string &sourceName,
                                        const LensRegistry &registry) {
    // A session of several views: its first view, as a one-view file would hold it.
    return parseSessionJson(text, sourceName, registry).view(0);
}

LensStackDescription readLensStackFile(const std::filesystem::path &path, const LensRegistry &registry) {
    LensStackDescription description =
        parseLensStackJson(readTextFile(path, "lens-stack file"), path.string(), registry);
    detail::resolveScenePaths(description, path);
    return description;
}

std::string lensStackJson(const LensStackDescription &description) {
    try {
        return prettyJson(detail::descriptionJson(description)) + "\n";
    } catch (const Json::exception &e) { // e.g. a label that is not valid UTF-8
        throw Error("lens-stack file", e.what());
    }
}

void writeLensStackFile(const std::filesystem::path &path, const LensStackDescription &description) {
    LensStackDescription relocated = description; // shares the lenses
    detail::relocateScenePaths(relocated, path);
    std::string text;
    try {
        text = lensStackJson(relocated);
    } catch (const Error &e) {
        throw Error(path.string(), e.problem());
    }
    writeFileAtomically(path, text);
}

std::shared_ptr<Lens> parseLensSpec(std::string_view spec, const LensRegistry &registry) {
    const JsonLocation where{"--lens", singleQuoted(spec), true};
    const std::size_t colon = spec.find(':');
    const std::string_view type = trimmed(spec.substr(0, colon));
    if (type.empty()) where.fail("expected type:key=value,... (e.g. layer:shape=ellipse,layers=1-)");

    Json lens{{"type", std::string(type)}};
    Json region = Json::object();
    Json properties = Json::object();
    const std::string_view settings = colon == std::string_view::npos ? std::string_view{} : spec.substr(colon + 1);
    std::string previousItem; // for the hint when a list value was not bracketed
    for (std::string_view item : splitOutsideBrackets(settings, where)) {
        item = trimmed(item);
        if (item.empty()) continue;
        const std::size_t equals = item.find('=');
        if (equals == std::string_view::npos) {
            std::string message = singleQuoted(item) + " is not key=value";
            const std::size_t previousEquals = previousItem.find('=');
            if (previousEquals != std::string::npos)
                message += "; a value with commas needs brackets: " + previousItem.substr(0, previousEquals + 1) +
                           "[" + previousItem.substr(previousEquals + 1) + "," + std::string(item) + "]";
            where.fail(message);
        }
        previousItem = std::string(item);
        const std::string key(trimmed(item.substr(0, equals)));
        const std::string_view text = trimmed(item.substr(equals + 1));
        const bool isRegionKey = std::ranges::find(kRegionKeys, key) != std::end(kRegionKeys);
        Json &target = isRegionKey ? region : (key == "label" || key == "enabled") ? lens : properties;
        if (target.contains(key)) where.key(key).fail("given twice");
        if (key == "label") target[key] = std::string(text);
        else if (isRegionKey || key == "enabled") target[key] = commandLineJson(text);
        // Property text is parsed by the property's declaration; brackets only protect commas.
        else if (text.size() >= 2 && text.front() == '[' && text.back() == ']')
            target[key] = std::string(text.substr(1, text.size() - 2));
        else target[key] = std::string(text);
    }
    if (!region.empty()) lens["region"] = std::move(region);
    if (!properties.empty()) lens["properties"] = std::move(properties);
    return readLens(lens, registry, where);
}

} // namespace mvcl
