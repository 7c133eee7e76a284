// Faulty plugins are contained: a lens whose contribute() throws or returns non-finite numbers,
// out-of-range values or a malformed map is disabled with a fault naming the lens and the
// problem, renders as if absent, and is kept (disabled, its values intact) by lens-stack files;
// an edit that would make a healthy lens faulty is refused and the lens goes on as it was.
// The fixture plugins (tests/lens/fixtures/FixtureFaulty.cpp) are in MVCL_FAULTY_PLUGIN_DIR.

#include <mvcl/lens/Lens.h>

#include <mvcl/core/Error.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace mvcl {
namespace {

struct FaultCase {
    const char *kind;
    const char *problem; ///< what the fault message must say
};

const FaultCase kFaults[] = {
    {"throws", "contribute() failed: fixture failure"},
    {"nan", "the colour map is not finite"},
    {"infinite", "primary rays: tMin must be finite and ≥ 0"},
    {"out-of-range", "shadow strength must lie in [0, 1]"},
    {"malformed", "ray shaping (sampleFromScreen) is not a finite affine map"},
};

std::string typeOf(const FaultCase &fault) { return std::string("fixture-faulty-") + fault.kind; }

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

class LensFault : public ::testing::TestWithParam<FaultCase> {
protected:
    static void SetUpTestSuite() {
        registry = new LensRegistry;
        for (const FaultCase &fault : kFaults)
            registry->loadModule(std::filesystem::path(MVCL_FAULTY_PLUGIN_DIR) / ("mvcl-lens-" + typeOf(fault) + ".so"));
    }
    static void TearDownTestSuite() { delete registry; }
    static LensRegistry *registry;
};

LensRegistry *LensFault::registry = nullptr;

TEST_P(LensFault, ANewLensOfAFaultyPluginIsDisabledWithAFaultNamingItAndTheProblem) {
    const std::shared_ptr<Lens> lens = registry->create(typeOf(GetParam()));
    const std::string fault = lens->fault();
    EXPECT_EQ(fault.rfind("lens '" + typeOf(GetParam()) + "': ", 0), 0u) << fault;
    EXPECT_TRUE(contains(fault, GetParam().problem)) << fault;
    EXPECT_FALSE(lens->isEnabled());
    EXPECT_FALSE(lens->snapshot()->enabled);
    EXPECT_EQ(lens->snapshot()->version, 1u);
    EXPECT_TRUE(lens->snapshot()->contribution.isIdentity());
}

TEST_P(LensFault, AnEditThatBreaksAHealthyLensIsRefusedAndTheLensGoesOn) {
    const std::shared_ptr<Lens> lens = registry->create(typeOf(GetParam()));
    lens->setEnabled(true);
    lens->setPropertyText("faulty", "false");
    lens->commit();
    EXPECT_TRUE(lens->fault().empty()) << "a sound commit clears the fault";
    const auto healthy = lens->snapshot();
    EXPECT_TRUE(healthy->enabled);

    lens->setPropertyText("faulty", "true");
    std::string error;
    try {
        lens->commit();
    } catch (const Error &e) {
        error = e.what();
    }
    EXPECT_TRUE(contains(error, "lens '" + typeOf(GetParam()) + "'")) << error;
    EXPECT_TRUE(contains(error, GetParam().problem)) << error;
    EXPECT_EQ(lens->snapshot(), healthy) << "a refused edit keeps the last sound snapshot";

    // Where a lens must exist whatever happens (a new lens, a file), it is disabled instead.
    lens->commitOrDisable();
    EXPECT_FALSE(lens->snapshot()->enabled);
    EXPECT_TRUE(contains(lens->fault(), GetParam().problem)) << lens->fault();
    EXPECT_EQ(lens->property("faulty").toBool(), true) << "the values are kept";
}

TEST_P(LensFault, ASessionRendersAFaultyLensAsAbsent) {
    const Scene scene = loadScene("builtin:cube-in-cube");
    const Tracer tracer(scene);
    RenderSettings settings;
    settings.width = 32;
    settings.height = 24;
    settings.samplesPerPixel = 1;
    const Camera camera = Camera::fromDesc(scene.cameras.front());
    const auto render = [&](const LensStack &stack) {
        RenderSession session(tracer);
        session.setSettings(settings);
        session.setCamera(camera);
        session.setLensStack(stack);
        session.renderUntilIdle();
        return session.image().pixels();
    };
    LensStack withFaulty;
    withFaulty.add(registry->create(typeOf(GetParam())));
    EXPECT_EQ(render(withFaulty), render(LensStack{}));
}

TEST_P(LensFault, AFileKeepsAFaultyLensDisabledWithItsValues) {
    const std::string type = typeOf(GetParam());
    const std::string json = R"({"scene": "builtin:cube-in-cube", "lenses": [
        {"type": ")" + type + R"(", "label": "broken", "enabled": true,
         "region": {"shape": "ellipse", "center": [0.25, 0.75], "size": [0.3, 0.2]}}]})";
    const LensStackDescription description = parseLensStackJson(json, "faulty.json", *registry);
    ASSERT_EQ(description.lenses.size(), 1);
    const Lens &lens = *description.lenses.lens(0);
    EXPECT_TRUE(contains(lens.fault(), GetParam().problem)) << lens.fault();
    EXPECT_FALSE(lens.snapshot()->enabled);
    EXPECT_EQ(lens.label(), "broken");
    EXPECT_EQ(lens.snapshot()->region.center(), glm::vec2(0.25f, 0.75f));

    // Written again, the lens is still there, disabled, with its region; and it reads back.
    const std::string written = lensStackJson(description);
    EXPECT_TRUE(contains(written, "\"type\": \"" + type + "\"")) << written;
    EXPECT_TRUE(contains(written, "\"enabled\": false")) << written;
    const LensStackDescription reread = parseLensStackJson(written, "faulty-again.json", *registry);
    EXPECT_TRUE(reread == description);
}

INSTANTIATE_TEST_SUITE_P(Faults, LensFault, ::testing::ValuesIn(kFaults),
                         [](const ::testing::TestParamInfo<FaultCase> &info) {
                             std::string name = info.param.kind;
                             std::erase(name, '-');
                             return name;
                         });

} // namespace
} // namespace mvcl
