// Lens-stack files and --lens specs: round trips over every registered lens type, errors that
// name the file and the JSON path, and atomic writes.

#define MVCL_LENS_STATIC_ID every_type_test_lens
#include <mvcl/lens/LensPlugin.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/core/Error.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/model/LayerTable.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace mvcl;
using test::errorOf;

namespace {

// A lens with one property of every type, so the file code is tested on all of them even
// where no plugin module declares some type.
const LensInfo kEveryTypeInfo{
    .name = "every-type",
    .description = "Test lens declaring one property of each type.",
    .properties = {PropertyDecl::boolean("flag", false, "a switch"),
                   PropertyDecl::integer("count", 3, -5, 1000, "", "a whole number"),
                   PropertyDecl::real("scale", 1.0, 0.001, 50.0, "px", "a bounded real"),
                   PropertyDecl::real("reach", 0.0, 0.0, std::numeric_limits<double>::infinity(), "scene units",
                                      "a real bounded on one side"),
                   PropertyDecl::color("tint", glm::vec3(0.5f), "a colour"),
                   PropertyDecl::choice("style", "plain", {"plain", "bold", "dotted"}, "a choice"),
                   PropertyDecl::layers("layers", layersFrom(1), "a layer set")},
    .defaultRayTypes = kAllRayTypes,
    .algebra = {},
};

class EveryTypeLens : public Lens {
public:
    EveryTypeLens() : Lens(kEveryTypeInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &, const LensContext &) const override {
        properties.boolean("flag");
        properties.integer("count");
        properties.real("scale");
        properties.real("reach");
        properties.color("tint");
        properties.choice("style");
        LensContribution contribution;
        contribution.visibility[size_t(RayType::Primary)].layerMask = properties.layers("layers");
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(EveryTypeLens, kEveryTypeInfo)

namespace {

/// The plugin modules of the build (layer, achromatic, shadow, ...) plus the test lens.
const LensRegistry &registry() {
    static const LensRegistry *instance = [] {
        auto *r = new LensRegistry;
        for (const Error &e : r->loadModules(LensRegistry::defaultSearchPath()))
            ADD_FAILURE() << "plugin skipped: " << e.what();
        r->add(mvcl_lens_plugin_every_type_test_lens(), "LensStackFileTest");
        return r;
    }();
    return *instance;
}

fs::path scratchDir(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-lens-stack-file-test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string readText(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void writeText(const fs::path &path, const std::string &text) { std::ofstream(path, std::ios::binary) << text; }

// --- random descriptions ---------------------------------------------------------------------

PropertyValue randomValue(const PropertyDecl &decl, std::mt19937 &rng) {
    // Unbounded sides get a generous finite range.
    const double lo = std::isinf(decl.minimum) ? -1e4 : decl.minimum;
    const double hi = std::isinf(decl.maximum) ? 1e4 : decl.maximum;
    const auto real = [&] { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    switch (decl.type) {
    case PropertyType::Bool: return PropertyValue::boolean(rng() % 2);
    case PropertyType::Int:
        return PropertyValue::integer(std::uniform_int_distribution<int>(int(std::max(lo, -1e9)),
                                                                         int(std::min(hi, 1e9)))(rng));
    case PropertyType::Real: return PropertyValue::real(real());
    case PropertyType::Color: return PropertyValue::color(glm::vec3(float(real()), float(real()), float(real())));
    case PropertyType::Choice: return PropertyValue::choice(decl.choices[rng() % decl.choices.size()]);
    case PropertyType::LayerSet: return PropertyValue::layerSet(uint32_t(rng()));
    case PropertyType::RayTypeSet: return PropertyValue::rayTypeSet(uint8_t(rng() % (kAllRayTypes + 1)));
    case PropertyType::Point3: return PropertyValue::point3({real(), real(), real()});
    case PropertyType::Vector3: return PropertyValue::vector3({real(), real(), real()});
    case PropertyType::Box3: {
        const glm::dvec3 a{real(), real(), real()}, b{real(), real(), real()};
        return PropertyValue::box3({glm::min(a, b), glm::max(a, b)});
    }
    case PropertyType::Transform: {
        glm::dmat4 m(1.0);
        m[3] = glm::dvec4(real(), real(), real(), 1.0);
        m[0][0] = 1.0 + std::abs(real()); // invertible: a scale and a shift
        return PropertyValue::transform(m);
    }
    }
    return {};
}

LensRegion randomRegion(std::mt19937 &rng) {
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    LensRegion region;
    switch (rng() % 3) {
    case 0: region = LensRegion::rectangle({unit(rng), unit(rng)}, {0.01f + unit(rng), 0.01f + unit(rng)}); break;
    case 1: region = LensRegion::ellipse({unit(rng), unit(rng)}, {0.01f + unit(rng), 0.01f + unit(rng)}); break;
    default: {
        std::vector<glm::vec2> points(3 + rng() % 6);
        for (glm::vec2 &p : points) p = {unit(rng), unit(rng)};
        region = LensRegion::polygon(std::move(points));
    }
    }
    region.setFeather(rng() % 2 ? 0.f : 20.f * unit(rng));
    region.setOutlineWidth(rng() % 2 ? 0.f : 4.f * unit(rng));
    region.setOutlineColor({unit(rng), unit(rng), unit(rng)});
    return region;
}

std::shared_ptr<Lens> randomLens(const std::string &type, std::mt19937 &rng) {
    static const char *const kLabels[] = {"reveal", "", "with \"quotes\", commas: and \\ slashes", "ünïcødé ∞"};
    std::shared_ptr<Lens> lens = registry().create(type);
    lens->setLabel(kLabels[rng() % std::size(kLabels)]);
    lens->setEnabled(rng() % 4 != 0);
    lens->setRegion(randomRegion(rng));
    for (const PropertyDecl &decl : lens->properties()) lens->setProperty(decl.name, randomValue(decl, rng));
    lens->commit();
    return lens;
}

LensStackDescription randomDescription(std::mt19937 &rng) {
    std::uniform_real_distribution<float> coordinate(-100.f, 100.f);
    LensStackDescription description;
    static const char *const kScenes[] = {"", "builtin:onion", "/models/engine parts/engine.glb"};
    description.scene = kScenes[rng() % std::size(kScenes)];
    switch (rng() % 3) {
    case 0: break;
    case 1: description.camera = LensStackCamera{.sceneCamera = rng() % 2 ? "Camera.001" : "2"}; break;
    default:
        description.camera = LensStackCamera{.sceneCamera = "",
                                             .eye = {coordinate(rng), coordinate(rng), coordinate(rng)},
                                             .target = {coordinate(rng), coordinate(rng), coordinate(rng)},
                                             .up = {0.f, 0.f, 1.f},
                                             .verticalFovDegrees = 1.f + float(rng() % 170)};
    }
    for (int i = int(rng() % 3); i > 0; --i)
        description.layerRules.add({"*part" + std::to_string(rng() % 100) + "?", int(rng() % kMaxLayers)});
    const std::vector<std::string> types = registry().lensTypes();
    for (int i = 1 + int(rng() % 6); i > 0; --i) description.lenses.add(randomLens(types[rng() % types.size()], rng));
    return description;
}

} // namespace

TEST(LensStackFile, RandomStacksOfEveryLensTypeRoundTripThroughAFile) {
    const std::vector<std::string> types = registry().lensTypes();
    ASSERT_TRUE(registry().contains("every-type"));
    const fs::path file = scratchDir("round-trip") / "stack.json";
    std::mt19937 rng(20070611);
    std::vector<int> seen(types.size(), 0);
    for (int round = 0; round < 60; ++round) {
        const LensStackDescription written = randomDescription(rng);
        for (const auto &lens : written.lenses.lenses())
            ++seen[std::find(types.begin(), types.end(), lens->typeName()) - types.begin()];
        writeLensStackFile(file, written);
        const LensStackDescription read = readLensStackFile(file, registry());
        ASSERT_TRUE(read == written) << "written:\n"
                                     << lensStackJson(written) << "read back:\n"
                                     << lensStackJson(read);
        // The text is canonical: writing what was read gives the same bytes.
        const std::string text = readText(file);
        writeLensStackFile(file, read);
        EXPECT_EQ(readText(file), text);
    }
    for (std::size_t i = 0; i < types.size(); ++i) EXPECT_GT(seen[i], 0) << types[i] << " never drawn";
}

TEST(LensStackFile, EqualityNoticesEveryPartOfALens) {
    std::mt19937 rng(7);
    const LensStackDescription a = parseLensStackJson(lensStackJson(randomDescription(rng)), "a", registry());
    const auto differs = [&](const std::function<void(LensStackDescription &)> &change) {
        LensStackDescription b = parseLensStackJson(lensStackJson(a), "b", registry());
        EXPECT_TRUE(a == b);
        change(b);
        return !(a == b);
    };
    EXPECT_TRUE(differs([](auto &d) { d.scene += "x"; }));
    EXPECT_TRUE(differs([](auto &d) { d.layerRules.add({"*extra*", 3}); }));
    EXPECT_TRUE(differs([](auto &d) { d.lenses.lens(0)->setLabel("changed"); }));
    EXPECT_TRUE(differs([](auto &d) {
        Lens &lens = *d.lenses.lens(0);
        lens.setEnabled(!lens.snapshot()->enabled);
        lens.commit();
    }));
    EXPECT_TRUE(differs([](auto &d) {
        Lens &lens = *d.lenses.lens(0);
        LensRegion region = lens.region();
        region.setFeather(region.feather() + 1.f);
        lens.setRegion(region);
        lens.commit();
    }));
    EXPECT_TRUE(differs([](auto &d) {
        Lens &lens = *d.lenses.lens(0);
        lens.setProperty("rays", PropertyValue::rayTypeSet(uint8_t(lens.property("rays").toRayTypeSet() ^ 1u)));
        lens.commit();
    }));
    EXPECT_TRUE(differs([](auto &d) { d.lenses.remove(0); }));
}

TEST(LensStackFile, JsonNumbersBooleansAndArraysConvertToThePropertyTypes) {
    const LensStackDescription d = parseLensStackJson(R"({"lenses": [{"type": "every-type", "properties": {
        "flag": true, "count": 42, "scale": 2.5, "reach": 7, "tint": [0.25, 0.5, 1],
        "style": "dotted", "layers": [0, 3], "rays": ["primary", "reflection"]}}]})",
                                                      "inline", registry());
    ASSERT_EQ(d.lenses.size(), 1);
    const Lens &lens = *d.lenses.lens(0);
    EXPECT_EQ(lens.property("flag"), PropertyValue::boolean(true));
    EXPECT_EQ(lens.property("count"), PropertyValue::integer(42));
    EXPECT_EQ(lens.property("scale"), PropertyValue::real(2.5));
    EXPECT_EQ(lens.property("reach"), PropertyValue::real(7.0));
    EXPECT_EQ(lens.property("tint"), PropertyValue::color({0.25f, 0.5f, 1.f}));
    EXPECT_EQ(lens.property("style"), PropertyValue::choice("dotted"));
    EXPECT_EQ(lens.property("layers"), PropertyValue::layerSet(layerBit(0) | layerBit(3)));
    EXPECT_EQ(lens.property("rays"),
              PropertyValue::rayTypeSet(rayTypeBit(RayType::Primary) | rayTypeBit(RayType::Reflection)));
    // Committed, not just staged.
    EXPECT_FALSE(lens.hasUncommittedChanges());
    EXPECT_EQ(lens.committedValues()[1], PropertyValue::integer(42));
}

TEST(LensStackFile, MissingKeysTakeDefaults) {
    const LensStackDescription d = parseLensStackJson(R"({"lenses": [{"type": "every-type"}]})", "inline", registry());
    EXPECT_TRUE(d.scene.empty());
    EXPECT_FALSE(d.camera);
    EXPECT_TRUE(d.layerRules.isEmpty());
    ASSERT_EQ(d.lenses.size(), 1);
    const Lens &lens = *d.lenses.lens(0);
    EXPECT_EQ(lens.label(), "every-type");
    EXPECT_TRUE(lens.snapshot()->enabled);
    EXPECT_EQ(lens.snapshot()->region, LensRegion());
    for (std::size_t i = 0; i < lens.properties().size(); ++i)
        EXPECT_EQ(lens.committedValues()[i], lens.properties()[i].defaultValue) << lens.properties()[i].name;
}

// "visibleLayers" is optional and written only when a layer is hidden, so the files of views
// that hide nothing stay as they were.
TEST(LensStackFile, VisibleLayersRoundTripAndAreLeftOutWhenAllAreVisible) {
    EXPECT_EQ(parseLensStackJson("{}", "inline", registry()).visibleLayers, kAllLayers);
    LensStackDescription d;
    d.scene = "builtin:onion";
    EXPECT_EQ(lensStackJson(d).find("visibleLayers"), std::string::npos);
    d.visibleLayers = layerBit(0) | layersFrom(2);
    const std::string text = lensStackJson(d);
    EXPECT_NE(text.find(R"("visibleLayers": "0,2-")"), std::string::npos) << text;
    EXPECT_EQ(parseLensStackJson(text, "inline", registry()), d);
    EXPECT_EQ(parseLensStackJson(R"({"visibleLayers": [1, 3]})", "inline", registry()).visibleLayers,
              layerBit(1) | layerBit(3));
    EXPECT_EQ(parseLensStackJson(R"({"visibleLayers": "none"})", "inline", registry()).visibleLayers, 0u);
    const std::string bad = errorOf([] { parseLensStackJson(R"({"visibleLayers": "0-40"})", "s.json", registry()); });
    EXPECT_EQ(bad.rfind("s.json: visibleLayers: ", 0), 0u) << bad;
    const std::string wrongType = errorOf([] { parseLensStackJson(R"({"visibleLayers": {}})", "s.json", registry()); });
    EXPECT_EQ(wrongType.rfind("s.json: visibleLayers: ", 0), 0u) << wrongType;
}

TEST(LensStackFile, RelativeScenePathsAreRelativeToTheFile) {
    const fs::path dir = scratchDir("relative");
    fs::create_directories(dir / "stacks");
    writeText(dir / "stacks" / "a.json", R"({"scene": "../models/engine.glb"})");
    EXPECT_EQ(fs::path(readLensStackFile(dir / "stacks" / "a.json", registry()).scene), dir / "models" / "engine.glb");

    LensStackDescription d;
    d.scene = (dir / "models" / "engine.glb").string();
    writeLensStackFile(dir / "stacks" / "b.json", d);
    EXPECT_NE(readText(dir / "stacks" / "b.json").find("\"../models/engine.glb\""), std::string::npos)
        << readText(dir / "stacks" / "b.json");
    d.scene = "builtin:onion";
    writeLensStackFile(dir / "stacks" / "b.json", d);
    EXPECT_EQ(readLensStackFile(dir / "stacks" / "b.json", registry()).scene, "builtin:onion");
}

// Unknown keys are errors at every level, named by their JSON path in the file.
TEST(LensStackFile, UnknownKeysAreRejectedWithTheirPath) {
    const fs::path dir = scratchDir("unknown-keys");
    const struct {
        const char *json;
        const char *expected; // the message after "<file>: "
    } cases[] = {
        {R"({"version": 1, "lensez": []})", "unknown key 'lensez'"},
        {R"({"camera": {"eye": [0,0,5], "target": [0,0,0], "fox": 40}})", "camera: unknown key 'fox'"},
        {R"({"camera": {"name": "front", "fov": 40}})", "camera: unknown key 'fov'"},
        {R"({"layerRules": [{"match": "*", "layer": 0, "colour": 1}]})", "layerRules: rule 0: unknown key 'colour'"},
        {R"({"lenses": [{"type": "every-type", "lable": "x"}]})", "lenses[0]: unknown key 'lable'"},
        {R"({"lenses": [{"type": "every-type", "region": {"shape": "ellipse", "centre": [0.5, 0.5]}}]})",
         "lenses[0].region: unknown key 'centre'"},
        {R"({"lenses": [{"type": "every-type"}, {"type": "every-type", "properties": {"cuont": 1}}]})",
         "lenses[1].properties: unknown property 'cuont' of lens 'every-type' (known: flag, count, scale, reach, "
         "tint, style, layers, rays)"},
    };
    for (const auto &c : cases) {
        const fs::path file = dir / "stack.json";
        writeText(file, c.json);
        const std::string message = errorOf([&] { readLensStackFile(file, registry()); });
        EXPECT_EQ(message.rfind(file.string() + ": " + c.expected, 0), 0u) << c.json << "\n" << message;
    }
}

// Malformed files fail with an mvcl::Error that names the file and, where there is one, the
// JSON path of the problem.
TEST(LensStackFile, BadFilesFailNamingTheFileAndThePath) {
    const fs::path dir = scratchDir("bad-files");
    const struct {
        const char *json;
        const char *path; // expected right after "<file>: "
        const char *detail;
    } cases[] = {
        {R"({"lenses": [)", "invalid JSON", "line 1"},
        {R"([1, 2])", "expected an object", "array"},
        {R"({"version": 3})", "version", "3"}, // 2 is a session of several views (SessionFile.h)
        {R"({"scene": 3})", "scene", "string"},
        {R"({"lenses": {"type": "every-type"}})", "lenses", "array"},
        {R"({"lenses": [{"label": "no type"}]})", "lenses[0]", "type"},
        {R"({"lenses": [{"type": "no-such-lens"}]})", "lenses[0].type", "no-such-lens"},
        {R"({"lenses": [{"type": "every-type", "enabled": "yes"}]})", "lenses[0].enabled", "true or false"},
        {R"({"lenses": [{"type": "every-type", "label": 5}]})", "lenses[0].label", "string"},
        {R"({"lenses": [{"type": "every-type", "properties": {"count": 1.5}}]})", "lenses[0].properties.count",
         "integer"},
        {R"({"lenses": [{"type": "every-type", "properties": {"count": 1001}}]})", "lenses[0].properties.count",
         "1001"},
        {R"({"lenses": [{"type": "every-type", "properties": {"scale": -1}}]})", "lenses[0].properties.scale", "-1"},
        // Range errors name the lens type as well as the path.
        {R"({"lenses": [{"type": "every-type", "properties": {"scale": -1}}]})", "lenses[0].properties.scale",
         "lens 'every-type': property 'scale'"},
        {R"({"lenses": [{"type": "every-type", "properties": {"flag": [1, 2]}}]})", "lenses[0].properties.flag",
         "true or false"},
        {R"({"lenses": [{"type": "every-type", "properties": {"tint": [1, 2]}}]})", "lenses[0].properties.tint",
         "colour"},
        {R"({"lenses": [{"type": "every-type", "properties": {"tint": {"r": 1}}}]})", "lenses[0].properties.tint",
         "object"},
        {R"({"lenses": [{"type": "every-type", "properties": {"style": "fancy"}}]})", "lenses[0].properties.style",
         "fancy"},
        {R"({"lenses": [{"type": "every-type", "properties": {"layers": "40"}}]})", "lenses[0].properties.layers",
         "40"},
        {R"({"lenses": [{"type": "every-type", "region": {"size": [-0.1, 0.3]}}]})", "lenses[0].region", "size"},
        {R"({"lenses": [{"type": "every-type", "region": {"points": [[0, 0], [1, 1]]}}]})", "lenses[0].region",
         "3 points"},
        {R"({"lenses": [{"type": "every-type", "region": {"shape": "star"}}]})", "lenses[0].region.shape", "star"},
        {R"({"lenses": [{"type": "every-type", "region": {"center": [0.5]}}]})", "lenses[0].region.center", "2"},
        {R"({"lenses": [{"type": "every-type", "region": {"feather": -2}}]})", "lenses[0].region", "feather"},
        {R"({"lenses": [{"type": "every-type", "region": {"shape": "ellipse", "points": [[0,0],[1,0],[0,1]]}}]})",
         "lenses[0].region.points", "polygon"},
        {R"({"camera": {"eye": [0, 0, 5]}})", "camera", "target"},
        {R"({"camera": {"eye": [1, 2, 3], "target": [1, 2, 3]}})", "camera", "same point"},
        {R"({"camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov": 180}})", "camera.fov", "180"},
        {R"({"layerRules": [{"match": "*", "layer": 99}]})", "layerRules", "99"},
        {R"({"layerRules": {"*": 0}})", "layerRules", "array"},
    };
    for (const auto &c : cases) {
        const fs::path file = dir / "bad.json";
        writeText(file, c.json);
        const std::string message = errorOf([&] { readLensStackFile(file, registry()); });
        EXPECT_EQ(message.rfind(file.string() + ": " + c.path, 0), 0u) << c.json << "\n" << message;
        EXPECT_NE(message.find(c.detail), std::string::npos) << c.json << "\n" << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    }
    EXPECT_NE(errorOf([&] { readLensStackFile(dir / "missing.json", registry()); }).find("missing.json"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { readLensStackFile(dir, registry()); }).find(dir.string()), std::string::npos);
}

// A write that fails half-way (here: the file-size limit) leaves the existing file as it was
// and no temporary file behind.
TEST(LensStackFile, AWriteRemovesTheTemporaryFilesOfKilledWriters) {
    const fs::path dir = scratchDir("temporaries");
    const fs::path file = dir / "session.json";
    // A process that has ended: its pid names no running process.
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ASSERT_GT(child, 0);
    ::waitpid(child, nullptr, 0);
    const fs::path killed = dir / ("session.json.part-" + std::to_string(child) + "-0");
    const fs::path running = dir / ("session.json.part-" + std::to_string(::getpid()) + "-999999");
    const fs::path otherFile = dir / ("other.json.part-" + std::to_string(child) + "-0");
    const fs::path notOurs = dir / "session.json.part-Ab12Cd";
    for (const fs::path &p : {killed, running, otherFile, notOurs}) writeText(p, "{\"half\": ");

    writeLensStackFile(file, LensStackDescription{});
    EXPECT_FALSE(fs::exists(killed)) << "left by a writer that no longer runs";
    EXPECT_TRUE(fs::exists(running)) << "a running writer's file is its own";
    EXPECT_TRUE(fs::exists(otherFile)) << "another file's temporaries wait for that file's next write";
    EXPECT_TRUE(fs::exists(notOurs)) << "not named as this writer names its files";
    EXPECT_NO_THROW(readLensStackFile(file, registry()));
}

TEST(LensStackFile, AFailedWriteLeavesTheExistingFileUntouched) {
    const fs::path dir = scratchDir("atomic");
    const fs::path file = dir / "session.json";
    const std::string original = "{\"version\": 1, \"scene\": \"builtin:onion\"}\n";
    writeText(file, original);
    std::mt19937 rng(3);
    LensStackDescription big;
    while (lensStackJson(big).size() < 4096) big.lenses.add(randomLens("every-type", rng));

    // Re-run the test binary for the child rather than fork a process that may have threads.
    const std::string previousStyle = GTEST_FLAG_GET(death_test_style);
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto writeUnderAFileSizeLimit = [&] {
        std::signal(SIGXFSZ, SIG_IGN); // make write() fail with EFBIG instead of killing us
        rlimit limit{};
        limit.rlim_cur = limit.rlim_max = 1024;
        setrlimit(RLIMIT_FSIZE, &limit);
        try {
            writeLensStackFile(file, big);
        } catch (const Error &e) {
            std::fprintf(stderr, "%s\n", e.what());
            std::exit(0);
        }
        std::exit(1);
    };
    EXPECT_EXIT(writeUnderAFileSizeLimit(),
        ::testing::ExitedWithCode(0), "session.json: write failed");
    GTEST_FLAG_SET(death_test_style, previousStyle);
    EXPECT_EQ(readText(file), original);
    std::vector<fs::path> left;
    for (const auto &entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename());
    EXPECT_EQ(left, std::vector<fs::path>{"session.json"});

    // Without the limit the same write replaces the file.
    writeLensStackFile(file, big);
    EXPECT_TRUE(readLensStackFile(file, registry()) == big);
}

TEST(LensStackFile, WritingIntoAMissingFolderCreatesIt) {
    const fs::path file = scratchDir("folders") / "a" / "b" / "stack.json";
    LensStackDescription d;
    d.scene = "builtin:cube-in-cube";
    writeLensStackFile(file, d);
    EXPECT_TRUE(readLensStackFile(file, registry()) == d);
}

// --- the command line's --lens ------------------------------------------------------------

TEST(LensSpec, KeysSetRegionLabelAndProperties) {
    const std::shared_ptr<Lens> lens = parseLensSpec(
        "every-type:shape=ellipse,center=[0.3,0.6],size=[0.2,0.1],feather=4,outline=1.5,outlineColor=[1,0,0],"
        "label=my lens,enabled=false,count=7,layers=[1,2],tint=[1,0,0.5],style=bold,scale=0.25,rays=primary",
        registry());
    const LensSnapshot &snapshot = *lens->snapshot();
    EXPECT_GT(snapshot.version, 0u);
    EXPECT_FALSE(snapshot.enabled);
    EXPECT_EQ(lens->label(), "my lens");
    LensRegion expected = LensRegion::ellipse({0.3f, 0.6f}, {0.2f, 0.1f});
    expected.setFeather(4.f);
    expected.setOutlineWidth(1.5f);
    expected.setOutlineColor({1.f, 0.f, 0.f});
    EXPECT_EQ(snapshot.region, expected);
    EXPECT_EQ(lens->property("count"), PropertyValue::integer(7));
    EXPECT_EQ(lens->property("layers"), PropertyValue::layerSet(layerBit(1) | layerBit(2)));
    EXPECT_EQ(lens->property("tint"), PropertyValue::color({1.f, 0.f, 0.5f}));
    EXPECT_EQ(lens->property("style"), PropertyValue::choice("bold"));
    EXPECT_EQ(lens->property("scale"), PropertyValue::real(0.25));
    EXPECT_EQ(lens->property("rays"), PropertyValue::rayTypeSet(rayTypeBit(RayType::Primary)));
}

TEST(LensSpec, PolygonsRangesAndBareTypes) {
    const std::shared_ptr<Lens> polygon =
        parseLensSpec("every-type: points=[[0.1,0.1],[0.9,0.2],[0.5,0.8]] , layers=2-", registry());
    EXPECT_EQ(polygon->snapshot()->region, LensRegion::polygon({{0.1f, 0.1f}, {0.9f, 0.2f}, {0.5f, 0.8f}}));
    EXPECT_EQ(polygon->property("layers"), PropertyValue::layerSet(layersFrom(2)));
    const std::shared_ptr<Lens> bare = parseLensSpec("every-type", registry());
    EXPECT_EQ(bare->committedValues(), registry().create("every-type")->committedValues());
}

TEST(LensSpec, ErrorsNameTheOptionTheSpecAndTheKey) {
    const struct {
        const char *spec;
        const char *expected;
    } cases[] = {
        {"every-type:cuont=3", "unknown property 'cuont'"},
        {"no-such-lens:count=3", "no-such-lens"},
        {":count=3", "type:key=value"},
        {"every-type:count", "'count' is not key=value"},
        // A list value without brackets: the message shows the bracket form.
        {"every-type:layers=1,3", "'3' is not key=value; a value with commas needs brackets: layers=[1,3]"},
        {"every-type:center=[0.3,0.5", "'[' without ']'"},
        {"every-type:center=0.3,0.5]", "']' without '['"},
        {"every-type:count=3,count=4", "count: given twice"},
        {"every-type:count=abc", "count: "},
        {"every-type:size=[-0.1,0.3]", "size"},
        {"every-type:center=[0.5]", "center"},
        {"every-type:shape=hexagon", "shape: unknown shape 'hexagon'"},
        {"every-type:points=[[0,0],[1,1]]", "3 points"},
        {"every-type:enabled=maybe", "enabled"},
    };
    for (const auto &c : cases) {
        const std::string message = errorOf([&] { parseLensSpec(c.spec, registry()); });
        EXPECT_EQ(message.rfind(std::string("--lens: '") + c.spec + "'", 0), 0u) << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.spec << "\n" << message;
    }
}
