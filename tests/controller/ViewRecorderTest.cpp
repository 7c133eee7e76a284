// ViewRecorder: a view's images at a fixed frame rate (repeated when the view draws slower,
// skipped when it draws faster).

#include <mvcl/controller/ViewRecorder.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/view/ImageIO.h>

#include <gtest/gtest.h>

#include <filesystem>

namespace fs = std::filesystem;
using namespace mvcl;

namespace {

Framebuffer grey(int width, int height, float value) {
    Framebuffer image(width, height);
    for (glm::vec3 &pixel : image.pixels()) pixel = glm::vec3(value);
    return image;
}

} // namespace

TEST(ViewRecorder, WritesFramesAtAFixedRateWhateverTheDrawingRate) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-view-recorder-test";
    fs::remove_all(dir);
    ViewRecorder recorder((dir / "%03d.png").string(), {8, 6}, 10.0);
    recorder.addImage(0.0, grey(8, 6, 0.1f));   // frame 0
    recorder.addImage(0.05, grey(8, 6, 0.2f));  // no frame due: skipped
    recorder.addImage(0.3, grey(8, 6, 0.4f));   // frames 1, 2, 3: the view drew slower
    EXPECT_EQ(recorder.framesWritten(), 4);
    recorder.finish();
    EXPECT_NEAR(readImage(dir / "000.png").at(0, 0).r, 0.1f, 0.01f);
    for (const char *frame : {"001.png", "002.png", "003.png"})
        EXPECT_NEAR(readImage(dir / frame).at(0, 0).r, 0.4f, 0.01f) << frame;
    EXPECT_FALSE(fs::exists(dir / "004.png"));
    const std::string message = test::errorOf([&] { recorder.addImage(0.4, grey(4, 4, 0.f)); });
    EXPECT_NE(message.find("the view changed size while recording (8x6 at the start)"), std::string::npos) << message;
}
