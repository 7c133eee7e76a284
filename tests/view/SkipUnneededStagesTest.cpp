// Leaving out the stages a policy does not need (RenderSettings::skipUnneededStages) must not
// change a single bit of the image: every scene here is rendered with the stages skipped and with
// every stage forced, and the images and ray counts are compared. Crafted scenes exercise each
// skip on its own; the built-in scenes, the model corpus and the demo lens stacks check that it
// holds on real data under lenses (including feathered edges that blend policies).

#include "TestRender.h"
#include "lens/InTreeLensRegistry.h"

#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/tracer/IntegratorPlan.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Renderer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace mvcl;

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;

struct SkipAndForce {
    test::TestRender skipping;
    test::TestRender forcing;
};

test::TestRender renderMap(const Tracer &tracer, const Camera &camera, const PolicyMap &policies, int spp,
                           StageSelection selection) {
    RenderSettings settings;
    settings.width = policies.width();
    settings.height = policies.height();
    settings.samplesPerPixel = spp;
    settings.threads = 2;
    settings.skipUnneededStages = selection == StageSelection::SkipUnneeded;
    test::TestRender out;
    out.stats = Renderer(tracer).render(camera, policies, settings, out.image);
    return out;
}

SkipAndForce renderBoth(const Tracer &tracer, const Camera &camera, const PolicyMap &policies, int spp = 1) {
    return {renderMap(tracer, camera, policies, spp, StageSelection::SkipUnneeded),
            renderMap(tracer, camera, policies, spp, StageSelection::ForceAll)};
}

std::size_t bitwiseDifferingPixels(const Framebuffer &a, const Framebuffer &b) {
    if (a.pixels().size() != b.pixels().size()) return std::max(a.pixels().size(), b.pixels().size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (std::bit_cast<uint32_t>(a.pixels()[i][c]) != std::bit_cast<uint32_t>(b.pixels()[i][c])) {
                ++differing;
                break;
            }
    return differing;
}

/// Same bits in every pixel; the same rays except the shadow rays the skipping render counted
/// as skipped; nothing counted as skipped when every stage is forced.
void expectSameImageAndRays(const SkipAndForce &r, const std::string &what) {
    const RayCounters &s = r.skipping.stats.rays;
    const RayCounters &f = r.forcing.stats.rays;
    EXPECT_EQ(bitwiseDifferingPixels(r.skipping.image, r.forcing.image), 0u) << what;
    EXPECT_EQ(s.primary, f.primary) << what;
    EXPECT_EQ(s.reflection, f.reflection) << what;
    EXPECT_EQ(s.refraction, f.refraction) << what;
    EXPECT_EQ(s.shadow + s.skippedShadowRays, f.shadow) << what;
    EXPECT_EQ(s.nonFiniteSamples, f.nonFiniteSamples) << what;
    EXPECT_EQ(f.skippedShadowRays + f.skippedTransparentWalks + f.skippedSecondaryChecks + f.skippedColorMaps, 0u)
        << what;
    // Per policy, the forced render charges exactly the skipped shadow rays more.
    ASSERT_EQ(r.skipping.stats.perPolicy.size(), r.forcing.stats.perPolicy.size()) << what;
    uint64_t skippedRays = 0, forcedRays = 0;
    for (std::size_t i = 0; i < r.skipping.stats.perPolicy.size(); ++i) {
        skippedRays += r.skipping.stats.perPolicy[i].rays;
        forcedRays += r.forcing.stats.perPolicy[i].rays;
    }
    EXPECT_EQ(skippedRays + s.skippedShadowRays, forcedRays) << what;
}

struct NamedPolicy {
    std::string name;
    RayPolicy policy;
};

/// Policies that turn each skip on and off: shadow masks with and without geometry, layer
/// lenses, shading switches, depth limits, shadow tints, empty ranges, clip volumes, colour.
std::vector<NamedPolicy> policyVariants() {
    std::vector<NamedPolicy> variants;
    auto add = [&](std::string name, auto edit) {
        RayPolicy p;
        edit(p);
        variants.push_back({std::move(name), p});
    };
    add("default", [](RayPolicy &) {});
    add("no shadow casters", [](RayPolicy &p) { p.query(RayType::Shadow).layerMask = 0; });
    add("casters on an empty layer", [](RayPolicy &p) { p.query(RayType::Shadow).layerMask = layerBit(20); });
    add("casters layer 0", [](RayPolicy &p) { p.query(RayType::Shadow).layerMask = layerBit(0); });
    add("casters layer 1", [](RayPolicy &p) { p.query(RayType::Shadow).layerMask = layerBit(1); });
    add("layer lens 1-", [](RayPolicy &p) {
        p.query(RayType::Primary).layerMask = layersFrom(1);
        p.query(RayType::Shadow).layerMask = layersFrom(1);
    });
    add("layer lens 2-, primary only", [](RayPolicy &p) { p.query(RayType::Primary).layerMask = layersFrom(2); });
    add("innermost layers 3-", [](RayPolicy &p) {
        for (RayQuery &q : p.visibility) q.layerMask = layersFrom(3);
    });
    add("shadows off", [](RayPolicy &p) { p.shading.shadows = false; });
    add("reflections off", [](RayPolicy &p) { p.shading.reflections = false; });
    add("refractions off", [](RayPolicy &p) { p.shading.refractions = false; });
    add("no secondary rays", [](RayPolicy &p) {
        p.shading.reflections = false;
        p.shading.refractions = false;
    });
    add("depth 0", [](RayPolicy &p) { p.shading.maxDepth = 0; });
    add("depth 1", [](RayPolicy &p) { p.shading.maxDepth = 1; });
    add("mirrors see layer 1 only", [](RayPolicy &p) {
        p.query(RayType::Reflection).layerMask = layerBit(1);
        p.query(RayType::Refraction).layerMask = layerBit(1);
    });
    add("tinted half shadows, no casters", [](RayPolicy &p) {
        p.shading.shadowStrength = 0.5f;
        p.shading.shadowTint = {0.3f, 0.3f, 0.5f};
        p.query(RayType::Shadow).layerMask = 0;
    });
    add("tinted half shadows, casters layer 0", [](RayPolicy &p) {
        p.shading.shadowStrength = 0.5f;
        p.shading.shadowTint = {0.3f, 0.3f, 0.5f};
        p.query(RayType::Shadow).layerMask = layerBit(0);
    });
    add("empty shadow range", [](RayPolicy &p) {
        p.query(RayType::Shadow).tMin = 1.f;
        p.query(RayType::Shadow).tMax = 0.5f;
    });
    add("short shadow range", [](RayPolicy &p) { p.query(RayType::Shadow).tMax = 0.5f; });
    add("shadow cutaway", [](RayPolicy &p) {
        RayQuery &q = p.query(RayType::Shadow);
        q.addClip(ClipVolume::halfSpace({0.f, 1.f, 0.f}, 0.5f, ClipVolume::Keep::Outside));
    });
    add("primary cutaway", [](RayPolicy &p) {
        RayQuery &q = p.query(RayType::Primary);
        q.addClip(ClipVolume::halfSpace({0.f, 0.f, 1.f}, 0.f, ClipVolume::Keep::Outside));
    });
    add("achromatic colour map", [](RayPolicy &p) {
        const glm::vec3 luma(0.2126f, 0.7152f, 0.0722f);
        p.color.matrix = glm::transpose(glm::mat3(luma, luma, luma));
    });
    return variants;
}

void expectSameUnderEveryVariant(const Tracer &tracer, const Camera &camera, const std::string &sceneName,
                                 RayCounters &skippedTotal) {
    for (const NamedPolicy &v : policyVariants()) {
        const SkipAndForce r = renderBoth(tracer, camera, PolicyMap(kWidth, kHeight, v.policy));
        expectSameImageAndRays(r, sceneName + ", " + v.name);
        skippedTotal += r.skipping.stats.rays;
    }
}

Material matte(glm::vec3 colour) {
    Material m;
    m.diffuse = colour;
    m.ambient = colour;
    m.specular = 0.3f;
    return m;
}

/// Every stage in one scene: a floor plane, an opaque ball (layer 0), a blocker above it
/// (layer 1), a mirror ball (layer 2) and a glass ball (layer 3), a point light and a sun.
Scene everyStageScene() {
    Scene s;
    s.name = "every stage";
    s.materials.push_back(matte({0.6f, 0.6f, 0.55f}));
    s.materials.push_back(matte({0.8f, 0.2f, 0.2f}));
    Material mirror = matte({0.1f, 0.1f, 0.1f});
    mirror.reflectivity = 0.8f;
    s.materials.push_back(mirror);
    Material glass = matte({0.05f, 0.05f, 0.05f});
    glass.transparency = 0.9f;
    glass.ior = 1.5f;
    s.materials.push_back(glass);
    s.planes.push_back({"floor", {0.f, 1.f, 0.f}, 0.f, 0, 0});
    s.spheres.push_back({"ball", {0.f, 1.f, 0.f}, 1.f, 1, 0});
    s.spheres.push_back({"blocker", {0.3f, 3.2f, 0.2f}, 0.5f, 1, 1});
    s.spheres.push_back({"mirror", {-2.2f, 0.8f, 0.5f}, 0.8f, 2, 2});
    s.spheres.push_back({"glass", {2.1f, 0.7f, 1.2f}, 0.7f, 3, 3});
    Light point;
    point.position = {1.f, 6.f, 3.f};
    point.intensity = glm::vec3(20.f);
    point.quadraticAttenuation = 1.f;
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.f, -0.3f));
    sun.intensity = glm::vec3(0.6f);
    s.lights = {point, sun};
    for (int layer = 0; layer < 4; ++layer) s.layers.ensure(layer);
    return s;
}

Camera everyStageCamera() { return Camera::lookAt({0.f, 3.f, 8.f}, {0.f, 1.f, 0.f}, {0.f, 1.f, 0.f}, 45.f); }

std::vector<fs::path> corpusModels() {
    std::vector<fs::path> models;
    const fs::path root = fs::path(MVCL_TEST_DATA_DIR) / "models";
    for (const fs::directory_entry &folder : fs::directory_iterator(root)) {
        if (!folder.is_directory() || folder.path().filename() == "EdgeCases") continue;
        for (const fs::directory_entry &e : fs::directory_iterator(folder.path()))
            if (e.path().extension() == ".glb") models.push_back(e.path());
    }
    std::sort(models.begin(), models.end());
    return models;
}

/// A stack like a user's: a feathered layer lens, a shadow lens whose casters exist nowhere, an
/// achromatic lens and a lens showing only the inner layers, overlapping in the middle.
LensStack corpusLensStack() {
    const LensRegistry &registry = test::inTreeLenses().registry;
    LensStack stack;
    for (const char *spec : {"layer:shape=ellipse,center=[0.45,0.5],size=[0.5,0.6],feather=4,layers=1-",
                             "shadow:shape=rectangle,center=[0.6,0.45],size=[0.5,0.5],casters=[20,21]",
                             "achromatic:shape=rectangle,center=[0.3,0.7],size=[0.4,0.3]",
                             "layer:shape=ellipse,center=[0.55,0.55],size=[0.3,0.3],feather=2,layers=2-"})
        stack.add(parseLensSpec(spec, registry));
    return stack;
}

fs::path lensAssetsDir() { return fs::path(MVCL_TEST_DATA_DIR) / ".." / ".." / "assets" / "lenses"; }

} // namespace

TEST(SkipUnneededStages, CraftedSceneIsBitIdenticalUnderEveryVariant) {
    const Scene scene = everyStageScene();
    const Tracer tracer(scene);
    RayCounters skipped;
    expectSameUnderEveryVariant(tracer, everyStageCamera(), scene.name, skipped);
    // Each kind of skip happened somewhere, so the comparisons above tested something.
    EXPECT_GT(skipped.skippedShadowRays, 0u);
    EXPECT_GT(skipped.skippedTransparentWalks, 0u);
    EXPECT_GT(skipped.skippedSecondaryChecks, 0u);
    EXPECT_GT(skipped.skippedColorMaps, 0u);
}

TEST(SkipUnneededStages, UnlitAndOpaqueVariantsOfTheCraftedScene) {
    // Without lights; and with the glass made opaque, so that no walk is ever forced.
    Scene unlit = everyStageScene();
    unlit.lights.clear();
    Scene opaque = everyStageScene();
    opaque.materials[3].transparency = 0.f;
    for (const Scene *scene : {&unlit, &opaque}) {
        const Tracer tracer(*scene);
        RayCounters skipped;
        expectSameUnderEveryVariant(tracer, everyStageCamera(), scene == &unlit ? "unlit" : "opaque", skipped);
        EXPECT_EQ(skipped.skippedTransparentWalks, 0u);
        if (scene == &unlit) {
            EXPECT_EQ(skipped.skippedShadowRays, 0u) << "no light, no shadow ray to skip";
        }
    }
}

TEST(SkipUnneededStages, BuiltinScenesAreBitIdenticalUnderEveryVariant) {
    for (const std::string &name : builtinSceneNames()) {
        const Scene scene = makeBuiltinScene(name);
        const Tracer tracer(scene);
        RayCounters skipped;
        expectSameUnderEveryVariant(tracer, Camera::fromDesc(scene.cameras.front()), "builtin:" + name, skipped);
        EXPECT_GT(skipped.skippedShadowRays, 0u) << name;
    }
}

TEST(SkipUnneededStages, ModelCorpusIsBitIdenticalUnderVariantsAndALensStack) {
    const std::vector<fs::path> models = corpusModels();
    ASSERT_GE(models.size(), 6u);
    const LensStack stack = corpusLensStack();
    RayCounters amber;
    for (const fs::path &model : models) {
        const Scene scene = loadScene(model.string());
        const Tracer tracer(scene);
        const Camera camera = Camera::framing(scene.bounds(), 40.f, float(kWidth) / float(kHeight));
        const std::string name = model.stem().string();
        RayCounters skipped;
        expectSameUnderEveryVariant(tracer, camera, name, skipped);
        const SkipAndForce lensed = renderBoth(tracer, camera, stack.compose(RayPolicy{}, kWidth, kHeight), 2);
        expectSameImageAndRays(lensed, name + " under the corpus lens stack");
        EXPECT_GT(lensed.skipping.stats.rays.skippedShadowRays, 0u) << name;
        if (name == "MosquitoInAmber") amber = skipped;
    }
    // The amber is the corpus's one transmissive material: hiding it from shadow rays turns the
    // walk into an any-hit query.
    EXPECT_GT(amber.skippedTransparentWalks, 0u);
}

TEST(SkipUnneededStages, DemoLensStacksAreBitIdentical) {
    const LensRegistry &registry = test::inTreeLenses().registry;
    std::vector<fs::path> stacks;
    for (const fs::directory_entry &e : fs::directory_iterator(lensAssetsDir()))
        if (e.path().extension() == ".json") stacks.push_back(e.path());
    ASSERT_GE(stacks.size(), 3u);
    for (const fs::path &file : stacks) {
        const LensStackDescription description = readLensStackFile(file, registry);
        SceneLoadOptions options;
        options.layerRules = description.layerRules;
        const Scene scene = loadScene(description.scene, options);
        const Tracer tracer(scene);
        const glm::vec3 origin(scene.worldOrigin);
        Camera camera = Camera::framing(scene.bounds(), 40.f, float(kWidth) / float(kHeight));
        if (description.camera && description.camera->sceneCamera.empty())
            camera = Camera::lookAt(description.camera->eye - origin, description.camera->target - origin,
                                    description.camera->up, description.camera->verticalFovDegrees);
        else if (!scene.cameras.empty())
            camera = Camera::fromDesc(scene.cameras.front());
        const SkipAndForce r = renderBoth(tracer, camera, description.lenses.compose(RayPolicy{}, kWidth, kHeight), 2);
        expectSameImageAndRays(r, file.filename().string());
    }
}
