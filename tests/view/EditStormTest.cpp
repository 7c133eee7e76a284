// Edit storms: four threads issue seeded random edits (camera, lens region, order, enabled,
// properties and type, layer visibility, render settings) against render sessions running in the
// background, while other threads copy their images and read their stats. Afterwards each idle
// session shows exactly the image a fresh session renders from the final state, bit for bit:
// a pixel that kept a sample taken under an earlier policy (or camera, or settings) would differ
// from it. Every pixel holds exactly the budget's samples, and the session's summed statistics
// agree with its per-pixel counts. scripts/ci-tsan.sh runs these under ThreadSanitizer.

#include <mvcl/view/RenderSession.h>

#include "TestRender.h"

#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/tracer/Tracer.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace mvcl {
namespace {

constexpr const char *kLensTypes[] = {"layer", "achromatic", "shadow", "magnifier"};
constexpr int kEditorThreads = 4;
constexpr int kEditsPerThread = 800;

/// What the storm leaves the sessions with, set once the editors are done: the reference.
RenderSettings finalSettings() {
    RenderSettings s;
    s.width = 48;
    s.height = 36;
    s.samplesPerPixel = 2;
    s.tileSize = 8;
    s.previewBudgetSeconds = 0.0;
    return s;
}

/// The shared state of one storm: the lens stack every session shows (its order and members
/// under `stackMutex`; each editor stages and commits only its own lens) and the sessions.
class Storm {
public:
    Storm(LensRegistry &registry, std::vector<RenderSession *> sessions, const Camera &camera)
        : m_registry(registry), m_sessions(std::move(sessions)), m_camera(camera) {
        for (int t = 0; t < kEditorThreads; ++t) {
            m_stack.add(newLens(kLensTypes[t], t));
            m_firstLenses.push_back(m_stack.lens(t));
        }
    }

    const LensStack &stack() const { return m_stack; }
    int edits() const { return m_edits.load(); }

    /// One editor: `count` edits drawn from `seed`, each sent to one session at random (lens
    /// edits to all of them, as linked views do).
    void edit(int editor, uint32_t seed, int count) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> unit(0.f, 1.f);
        // The lens this editor was given, not the one at its index now: another editor may have
        // reordered the stack already, and two editors would then stage one lens at once.
        std::shared_ptr<Lens> mine = m_firstLenses[std::size_t(editor)];
        for (int e = 0; e < count; ++e) {
            RenderSession &session = *m_sessions[rng() % m_sessions.size()];
            switch (rng() % 8) {
            case 0: { // orbit a little
                const float angle = 0.2f * (unit(rng) - 0.5f);
                const glm::vec3 offset = m_camera.eye() - m_camera.target();
                const glm::vec3 turned{offset.x * std::cos(angle) - offset.z * std::sin(angle), offset.y,
                                       offset.x * std::sin(angle) + offset.z * std::cos(angle)};
                session.setCamera(Camera::lookAt(m_camera.target() + turned, m_camera.target(), m_camera.up(),
                                                 m_camera.verticalFovDegrees()));
                break;
            }
            case 1: { // drag or resize my lens
                LensRegion region = mine->region();
                region.setCenter({unit(rng), unit(rng)});
                region.setSize({0.15f + 0.5f * unit(rng), 0.15f + 0.5f * unit(rng)});
                region.setFeather(rng() % 2 ? 0.f : 2.f * unit(rng));
                mine->setRegion(region);
                commitAndShow(*mine);
                break;
            }
            case 2: // a property every lens has
                mine->setPropertyText("rays", rng() % 2 ? "primary" : "primary,shadow");
                commitAndShow(*mine);
                break;
            case 3:
                mine->setEnabled(!mine->isEnabled());
                commitAndShow(*mine);
                break;
            case 4: { // reorder the stack
                std::lock_guard lock(m_stackMutex);
                m_stack.move(int(rng() % unsigned(m_stack.size())), int(rng() % unsigned(m_stack.size())));
                showLocked();
                break;
            }
            case 5: { // replace my lens by one of another type
                std::shared_ptr<Lens> replacement = newLens(kLensTypes[rng() % 4], int(rng() % 16));
                std::lock_guard lock(m_stackMutex);
                for (int i = 0; i < m_stack.size(); ++i)
                    if (m_stack.lens(i) == mine) {
                        m_stack.remove(i);
                        m_stack.insert(i, replacement);
                    }
                mine = std::move(replacement);
                showLocked();
                break;
            }
            case 6: { // layer visibility: hide the outer cube or show everything
                RayPolicy base;
                base.query(RayType::Primary).layerMask = rng() % 2 ? kAllLayers : ~uint32_t(1);
                session.setBasePolicy(base);
                break;
            }
            case 7: { // settings: size, seed, tiles, threads, budgets, previews
                RenderSettings s = finalSettings();
                s.width = rng() % 2 ? 48 : 40;
                s.height = rng() % 2 ? 36 : 30;
                s.seed = rng() % 2;
                s.tileSize = rng() % 2 ? 8 : 16;
                s.threads = int(rng() % 3);
                s.samplesPerPixel = 1 + int(rng() % 3);
                s.sampling = rng() % 2 ? SamplingMode::Fixed : SamplingMode::Progressive;
                s.maxSamplesPerPixel = 4;
                s.previewBudgetSeconds = rng() % 2 ? 0.0 : 1e-6; // 1 µs: every camera edit previews
                session.setSettings(s);
                break;
            }
            }
            ++m_edits;
            std::this_thread::sleep_for(std::chrono::microseconds(rng() % 1000));
        }
    }

private:
    std::shared_ptr<Lens> newLens(const char *type, int variant) {
        std::shared_ptr<Lens> lens;
        {
            std::lock_guard lock(m_registryMutex);
            lens = m_registry.create(type);
        }
        const float shift = 0.05f * float(variant % 8);
        lens->setRegion(LensRegion::ellipse({0.3f + shift, 0.4f + shift}, {0.4f, 0.5f}));
        lens->commit();
        return lens;
    }

    void commitAndShow(Lens &lens) {
        lens.commit();
        std::lock_guard lock(m_stackMutex);
        showLocked();
    }

    void showLocked() {
        for (RenderSession *session : m_sessions) session->setLensStack(m_stack);
    }

    LensRegistry &m_registry;
    std::mutex m_registryMutex;
    std::vector<RenderSession *> m_sessions;
    const Camera m_camera;
    std::mutex m_stackMutex;
    LensStack m_stack;
    std::vector<std::shared_ptr<Lens>> m_firstLenses; ///< editor t's lens at the start
    std::atomic<int> m_edits{0};
};

class EditStorm : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        registry = new LensRegistry;
        for (const char *name : kLensTypes)
            registry->loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / (std::string("mvcl-lens-") + name + ".so"));
    }
    static void TearDownTestSuite() { delete registry; }

    /// Storms `sessionCount` background sessions on one tracer, then checks each against a fresh
    /// session rendering the final state.
    static void storm(int sessionCount, uint32_t seed) {
        const Scene scene = loadScene("builtin:cube-in-cube");
        const Tracer tracer(scene);
        const Camera camera = Camera::fromDesc(scene.cameras.front());
        std::vector<std::unique_ptr<RenderSession>> sessions;
        std::vector<RenderSession *> raw;
        for (int i = 0; i < sessionCount; ++i) {
            sessions.push_back(std::make_unique<RenderSession>(tracer));
            sessions.back()->setSettings(finalSettings());
            sessions.back()->setCamera(camera);
            raw.push_back(sessions.back().get());
        }
        Storm storm(*registry, raw, camera);
        for (RenderSession *session : raw) {
            session->setLensStack(storm.stack());
            session->start();
        }

        // Readers: what a viewer's UI thread does every frame.
        std::atomic<bool> editing{true};
        std::atomic<int> copies{0}, badCopies{0}, countersWentBack{0};
        std::vector<std::thread> readers;
        for (RenderSession *session : raw)
            readers.emplace_back([&, session] {
                Framebuffer shown;
                PixelRect changed;
                uint64_t passesSeen = 0;
                while (editing.load()) {
                    if (session->copyImage(shown, changed)) {
                        ++copies;
                        if (test::nonFinitePixels(shown) != 0 || changed.x1 > shown.width() || changed.y1 > shown.height())
                            ++badCopies;
                    }
                    const uint64_t passes = session->passCount();
                    if (passes < passesSeen) ++countersWentBack;
                    passesSeen = passes;
                    (void)session->lastPass();
                    (void)session->convergence();
                    std::this_thread::sleep_for(std::chrono::microseconds(300));
                }
            });
        std::vector<uint64_t> passesBefore;
        for (RenderSession *session : raw) passesBefore.push_back(session->passCount());
        std::vector<std::thread> editors;
        for (int t = 0; t < kEditorThreads; ++t)
            editors.emplace_back([&, t] { storm.edit(t, seed + uint32_t(t), kEditsPerThread); });
        for (std::thread &editor : editors) editor.join();

        // The final state, the same for every session.
        const RenderSettings settings = finalSettings();
        for (RenderSession *session : raw) {
            session->setSettings(settings);
            session->setCamera(camera);
            session->setBasePolicy(RayPolicy{});
            session->setLensStack(storm.stack());
        }
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
        for (RenderSession *session : raw)
            while (session->hasWork() && std::chrono::steady_clock::now() < deadline)
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
        editing = false;
        for (std::thread &reader : readers) reader.join();
        for (RenderSession *session : raw) session->stop();

        EXPECT_EQ(storm.edits(), kEditorThreads * kEditsPerThread);
        EXPECT_GT(copies.load(), 0);
        EXPECT_EQ(badCopies.load(), 0) << "a copied image had non-finite pixels or a changed area outside it";
        EXPECT_EQ(countersWentBack.load(), 0) << "passCount() went backwards";

        RenderSession fresh(tracer);
        fresh.setSettings(settings);
        fresh.setCamera(camera);
        fresh.setLensStack(storm.stack());
        fresh.renderUntilIdle();
        const size_t pixels = size_t(settings.width) * size_t(settings.height);
        for (size_t i = 0; i < raw.size(); ++i) {
            RenderSession &session = *raw[i];
            SCOPED_TRACE("session " + std::to_string(i) + " of " + std::to_string(raw.size()));
            EXPECT_FALSE(session.hasWork()) << "not idle five minutes after the storm";
            EXPECT_GT(session.passCount(), passesBefore[i] + 10) << "the storm hardly ran passes";
            ASSERT_EQ(session.image().width(), settings.width);
            ASSERT_EQ(session.image().height(), settings.height);
            EXPECT_EQ(session.image().pixels(), fresh.image().pixels()) << "the idle image is not the final state's";
            // Every pixel holds exactly its budget; the summed statistics agree with the pixels.
            const std::vector<uint32_t> counts = session.sampleCounts();
            ASSERT_EQ(counts.size(), pixels);
            for (uint32_t count : counts) ASSERT_EQ(count, uint32_t(settings.samplesPerPixel));
            const ConvergenceStats c = session.convergence();
            EXPECT_TRUE(c.isConverged);
            EXPECT_EQ(c.minSamples, settings.samplesPerPixel);
            EXPECT_EQ(c.maxSamples, settings.samplesPerPixel);
            EXPECT_EQ(c.meanSamples, double(std::accumulate(counts.begin(), counts.end(), uint64_t(0))) / double(pixels));
            EXPECT_EQ(c.activePixels, 0u);
        }
    }

    static LensRegistry *registry;
};

LensRegistry *EditStorm::registry = nullptr;

TEST_F(EditStorm, OneBackgroundSessionEndsOnTheFinalStateBitForBit) { storm(1, 1000); }

TEST_F(EditStorm, TwoSessionsSharingOneTracerEachEndOnTheFinalStateBitForBit) { storm(2, 2000); }

} // namespace
} // namespace mvcl
