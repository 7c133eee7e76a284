#include <mvcl/io/SessionFile.h>

#include "LensStackFile_p.h"

#include <mvcl/core/Error.h>

#include <algorithm>

namespace mvcl {

namespace {

using namespace detail; // the JSON file helpers

constexpr int kSessionVersion = 2;
/// A layout shows at most four views; a file holds no more.
constexpr std::size_t kMaxViews = 4;

constexpr std::string_view kSceneKeys[] = {"scene", "layerRules", "layerContact", "memoryBudgetMiB", "layerNames"};
constexpr std::string_view kTopKeys[] = {"version",         "scene", "layerRules", "layerContact", "memoryBudgetMiB",
                                         "layerNames",      "views", "links",      "layout", "focus"};
constexpr std::string_view kViewKeys[] = {"camera", "visibleLayers", "lenses", "compare"};
constexpr std::string_view kCompareKeys[] = {"divider", "lenses"};
constexpr std::string_view kLinkKeys[] = {"views", "camera", "lenses", "layers"};

/// The keys of `object` named in `keys`, in the object's order.
Json subset(const Json &object, std::span<const std::string_view> keys) {
    Json part = Json::object();
    for (const auto &[key, value] : object.items())
        if (std::ranges::find(keys, key) != std::end(keys)) part[key] = value;
    return part;
}

int readIndex(const Json &value, std::size_t count, const JsonLocation &where) {
    if (!value.is_number_integer() || value.get<long long>() < 0 || value.get<long long>() >= (long long)count)
        where.fail("expected a view index 0.." + std::to_string(count - 1) + ", got " + value.dump());
    return int(value.get<long long>());
}

SessionViewDescription readView(const Json &value, const LensRegistry &registry, const JsonLocation &where) {
    expectObject(value, where);
    rejectUnknownKeys(value, kViewKeys, where);
    const LensStackDescription read = readDescription(subset(value, std::span(kViewKeys).first(3)), registry, where);
    SessionViewDescription view;
    view.camera = read.camera;
    view.visibleLayers = read.visibleLayers;
    view.lenses = read.lenses;
    if (value.contains("compare")) {
        const JsonLocation compareWhere = where.key("compare");
        const Json &compare = expectObject(value["compare"], compareWhere);
        rejectUnknownKeys(compare, kCompareKeys, compareWhere);
        CompareDescription description;
        if (compare.contains("divider")) {
            description.divider = readNumber(compare["divider"], compareWhere.key("divider"));
            if (!(description.divider >= 0.f && description.divider <= 1.f))
                compareWhere.key("divider").fail("must be in 0..1 (a fraction of the view's width)");
        }
        description.lenses = readDescription(subset(compare, std::span(kCompareKeys).last(1)), registry, compareWhere).lenses;
        view.compare = std::move(description);
    }
    return view;
}

ViewLink readLink(const Json &value, std::size_t viewCount, const JsonLocation &where) {
    expectObject(value, where);
    rejectUnknownKeys(value, kLinkKeys, where);
    const JsonLocation viewsWhere = where.key("views");
    if (!value.contains("views") || !value["views"].is_array() || value["views"].size() != 2)
        viewsWhere.fail("expected the two linked views, [a, b]");
    ViewLink link;
    const int a = readIndex(value["views"][0], viewCount, viewsWhere.index(0));
    const int b = readIndex(value["views"][1], viewCount, viewsWhere.index(1));
    if (a == b) viewsWhere.fail("a view cannot be linked to itself");
    link.a = std::min(a, b);
    link.b = std::max(a, b);
    for (LinkAspect aspect : {LinkAspect::Camera, LinkAspect::Lenses, LinkAspect::Layers}) {
        const char *name = linkAspectName(aspect);
        if (value.contains(name)) link.set(aspect, readBool(value[name], where.key(name)));
    }
    return link;
}

SessionDescription readVersion2(const Json &document, const LensRegistry &registry, const JsonLocation &where) {
    for (const char *viewKey : {"camera", "visibleLayers", "lenses"})
        if (document.contains(viewKey))
            where.key(viewKey).fail("a version-2 file keeps this in each of its \"views\"");
    rejectUnknownKeys(document, kTopKeys, where);
    SessionDescription session;
    session.common = readDescription(subset(document, kSceneKeys), registry, where);
    const JsonLocation viewsWhere = where.key("views");
    if (!document.contains("views")) where.fail("missing \"views\"");
    const Json &views = document["views"];
    if (!views.is_array() || views.empty() || views.size() > kMaxViews)
        viewsWhere.fail("expected an array of 1 to " + std::to_string(kMaxViews) + " views");
    for (std::size_t i = 0; i < views.size(); ++i) session.views.push_back(readView(views[i], registry, viewsWhere.index(i)));
    if (document.contains("links")) {
        const JsonLocation linksWhere = where.key("links");
        const Json &links = document["links"];
        if (!links.is_array()) linksWhere.fail("expected an array of links");
        std::vector<ViewLink> read; // empty ones too, for the check
        for (std::size_t i = 0; i < links.size(); ++i) {
            const ViewLink link = readLink(links[i], views.size(), linksWhere.index(i));
            for (const ViewLink &earlier : read)
                if (earlier.joins(link.a, link.b))
                    linksWhere.index(i).fail("views " + std::to_string(link.a) + " and " + std::to_string(link.b) +
                                             " are linked twice");
            read.push_back(link);
            if (!link.isEmpty()) session.links.push_back(link); // a link of no aspect links nothing
        }
    }
    if (document.contains("layout")) {
        try {
            session.layout = parseViewLayout(readString(document["layout"], where.key("layout")), where.source);
        } catch (const Error &e) {
            where.key("layout").fail(e.problem());
        }
    }
    if (document.contains("focus")) session.focus = readIndex(document["focus"], views.size(), where.key("focus"));
    return session;
}

Json viewJson(const SessionViewDescription &view) {
    LensStackDescription asFile;
    asFile.camera = view.camera;
    asFile.visibleLayers = view.visibleLayers;
    asFile.lenses = view.lenses;
    Json json = subset(descriptionJson(asFile), std::span(kViewKeys).first(3));
    if (const auto &compare = view.compare) {
        LensStackDescription right;
        right.lenses = compare->lenses;
        json["compare"] = {{"divider", shortestDouble(compare->divider)}, {"lenses", descriptionJson(right)["lenses"]}};
    }
    return json;
}

Json version2Json(const SessionDescription &session) {
    Json json;
    json["version"] = kSessionVersion;
    const Json scenePart = subset(descriptionJson(session.common), kSceneKeys);
    for (const auto &[key, value] : scenePart.items()) json[key] = value;
    Json views = Json::array();
    for (const SessionViewDescription &view : session.views) views.push_back(viewJson(view));
    json["views"] = std::move(views);
    if (!session.links.empty()) {
        Json links = Json::array();
        for (const ViewLink &link : session.links)
            links.push_back({{"views", {link.a, link.b}}, {"camera", link.camera}, {"lenses", link.lenses}, {"layers", link.layers}});
        json["links"] = std::move(links);
    }
    json["layout"] = viewLayoutName(session.layout);
    json["focus"] = session.focus;
    return json;
}

} // namespace

LensStackDescription SessionDescription::view(int index) const {
    LensStackDescription description = common;
    if (views.empty()) return description;
    const SessionViewDescription &v = views[std::size_t(std::clamp(index, 0, int(views.size()) - 1))];
    description.camera = v.camera;
    description.visibleLayers = v.visibleLayers;
    description.lenses = v.lenses;
    return description;
}

SessionDescription SessionDescription::fromView(const LensStackDescription &description) {
    SessionDescription session;
    session.common = description;
    session.common.camera.reset();
    session.common.visibleLayers = kAllLayers;
    session.common.lenses = {};
    session.views.push_back({description.camera, description.visibleLayers, description.lenses, std::nullopt});
    return session;
}

bool SessionDescription::isSingleView() const {
    return views.size() == 1 && !views.front().compare && links.empty() && layout == ViewLayout::Single && focus == 0;
}

SessionDescription parseSessionJson(std::string_view text, const std::string &sourceName, const LensRegistry &registry) {
    const Json document = parseJsonDocument(text, sourceName);
    const JsonLocation where{sourceName, "", false};
    expectObject(document, where);
    if (document.contains("version")) {
        const Json &version = document["version"];
        if (!version.is_number_integer() || (version.get<long long>() != 1 && version.get<long long>() != kSessionVersion))
            where.key("version").fail("this build reads versions 1 and 2, got " + version.dump());
        if (version.get<long long>() == kSessionVersion) return readVersion2(document, registry, where);
    }
    return SessionDescription::fromView(readDescription(document, registry, where));
}

SessionDescription readSessionFile(const std::filesystem::path &path, const LensRegistry &registry) {
    SessionDescription session = parseSessionJson(readTextFile(path, "lens-stack file"), path.string(), registry);
    resolveScenePaths(session.common, path);
    return session;
}

std::string sessionJson(const SessionDescription &session) {
    if (session.isSingleView()) return lensStackJson(session.view(0));
    try {
        return prettyJson(version2Json(session)) + "\n";
    } catch (const Json::exception &e) { // e.g. a label that is not valid UTF-8
        throw Error("session file", e.what());
    }
}

void writeSessionFile(const std::filesystem::path &path, const SessionDescription &session) {
    SessionDescription relocated = session; // shares the lenses
    relocateScenePaths(relocated.common, path);
    std::string text;
    try {
        text = sessionJson(relocated);
    } catch (const Error &e) {
        throw Error(path.string(), e.problem());
    }
    writeFileAtomically(path, text);
}

} // namespace mvcl
