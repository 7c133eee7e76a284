#pragma once
// A Controller on the small built-in scene with the in-tree lens plugins, and helpers that
// send synthetic pointer and key events the way a window system would.

#include <mvcl/controller/Controller.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/model/Scene.h>

#include <gtest/gtest.h>

#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

#include <filesystem>
#include <memory>
#include <string>

namespace mvcl::test {

class ControllerFixture : public ::testing::Test {
protected:
    static constexpr int kWidth = 160;
    static constexpr int kHeight = 120;

    static void SetUpTestSuite() {
        registry = new LensRegistry;
        for (const char *name : {"layer", "achromatic", "shadow", "magnifier"})
            registry->loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) /
                                 (std::string("mvcl-lens-") + name + ".so"));
    }
    static void TearDownTestSuite() {
        delete registry;
        registry = nullptr;
    }

    static RenderSettings smallSettings() {
        RenderSettings settings;
        settings.width = kWidth;
        settings.height = kHeight;
        settings.samplesPerPixel = 1;
        settings.previewBudgetSeconds = 0.0;
        return settings;
    }

    static ViewRequest cubeRequest() {
        ViewRequest request;
        request.source = "builtin:cube-in-cube";
        return request;
    }

    static std::unique_ptr<Controller> makeController(const ViewRequest &request = cubeRequest()) {
        return std::make_unique<Controller>(*registry, request, smallSettings());
    }

    /// A scratch folder of this test, empty.
    static std::filesystem::path scratchFolder() {
        const ::testing::TestInfo *info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::filesystem::path folder = std::filesystem::temp_directory_path() / "mvcl-controller-test" /
                                       (std::string(info->test_suite_name()) + "." + info->name());
        std::filesystem::remove_all(folder);
        std::filesystem::create_directories(folder);
        return folder;
    }

    /// Press at `from`, move in `steps` equal moves to `to`, release there.
    static void drag(Controller &controller, const glm::vec2 &from, const glm::vec2 &to,
                     PointerButton button = PointerButton::Left, KeyModifier modifiers = KeyModifier::None,
                     int steps = 4) {
        controller.handle(InputEvent::pointerPress(from, button, modifiers));
        for (int i = 1; i <= steps; ++i)
            controller.handle(InputEvent::pointerMove(from + (to - from) * (float(i) / float(steps)), modifiers));
        controller.handle(InputEvent::pointerRelease(to, button, modifiers));
    }

    static void press(Controller &controller, Key key, KeyModifier modifiers = KeyModifier::None) {
        controller.handle(InputEvent::keyPress(key, modifiers));
    }

    /// Framebuffer pixel of a normalised position in the test view.
    static glm::vec2 pixelOf(const glm::vec2 &normalized) { return normalized * glm::vec2(kWidth, kHeight); }

    static LensRegistry *registry;
};

inline LensRegistry *ControllerFixture::registry = nullptr;

/// Where `point` (scene space) appears in a width × height image of `camera`, in pixels.
inline glm::vec2 projectToPixel(const Camera &camera, const glm::vec3 &point, int width, int height) {
    const glm::mat3 &axes = camera.sceneFromCamera();
    const glm::vec3 p = glm::transpose(axes) * (point - camera.eye());
    const float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees()) * 0.5f);
    const float aspect = float(width) / float(height);
    const float sx = p.x / -p.z / (tanHalf * aspect);
    const float sy = p.y / -p.z / tanHalf;
    return {(sx + 1.f) * 0.5f * float(width), (1.f - sy) * 0.5f * float(height)};
}

} // namespace mvcl::test
