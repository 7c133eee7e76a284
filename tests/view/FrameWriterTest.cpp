// FrameWriter: numbered frame files from a pattern, what is checked before anything renders, and
// whole files only.

#include <mvcl/view/FrameWriter.h>

#include <mvcl/testing/ErrorOf.h>

#include <mvcl/view/ImageIO.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace mvcl;
using test::errorOf;

namespace {

fs::path scratch(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-frame-writer-test" / name;
    fs::remove_all(dir);
    return dir;
}

Framebuffer grey(int width, int height, float value) {
    Framebuffer image(width, height);
    for (glm::vec3 &pixel : image.pixels()) pixel = glm::vec3(value);
    return image;
}

} // namespace

TEST(FrameWriter, NamesFramesFromAPrintfStyleNumber) {
    EXPECT_EQ(FrameWriter::frameFileName("frames/%04d.png", 7), "frames/0007.png");
    EXPECT_EQ(FrameWriter::frameFileName("f%d.png", 123), "f123.png");
    EXPECT_EQ(FrameWriter::frameFileName("100%%/f%03d.jpg", 5), "100%/f005.jpg");
    EXPECT_EQ(FrameWriter::frameFileName("take%02d-%%.png", 12345), "take12345-%.png");
    EXPECT_TRUE(FrameWriter::isVideo("clip.MP4"));
    EXPECT_TRUE(FrameWriter::isVideo("out/clip.mkv"));
    EXPECT_FALSE(FrameWriter::isVideo("frames/%04d.png"));
}

TEST(FrameWriter, WritesEachFrameAsAWholeFileInACreatedFolder) {
    const fs::path dir = scratch("sequence");
    FrameWriter writer((dir / "nested" / "%03d.png").string(), 8, 6, 30.0);
    EXPECT_TRUE(fs::is_directory(dir / "nested")); // made before the first frame renders
    writer.write(4, grey(8, 6, 0.25f));
    writer.write(5, grey(8, 6, 0.5f));
    writer.finish();
    EXPECT_FALSE(writer.writesVideo());
    EXPECT_NEAR(readImage(dir / "nested" / "004.png").at(3, 3).r, 0.25f, 0.01f);
    EXPECT_NEAR(readImage(dir / "nested" / "005.png").at(3, 3).r, 0.5f, 0.01f);
    for (const auto &entry : fs::directory_iterator(dir / "nested"))
        EXPECT_EQ(entry.path().extension(), ".png") << entry.path(); // no temporary left behind
    EXPECT_NE(errorOf([&] { writer.write(6, grey(4, 4, 0.f)); }).find("frame 6 is 4x4, not 8x6"), std::string::npos);
}

TEST(FrameWriter, PatternsAndFoldersAreCheckedBeforeAnythingRenders) {
    const fs::path dir = scratch("bad");
    fs::create_directories(dir);
    for (const std::string pattern : {"frame.png", "%d-%d.png", "%s.png"}) {
        const std::string target = (dir / pattern).string();
        EXPECT_EQ(errorOf([&] { FrameWriter(target, 4, 4, 30.0); }),
                  target + ": numbered frames need one frame number in the name, such as frames/%04d.png "
                           "(or write a video: .mp4, .mkv, .mov)");
    }
    std::ofstream(dir / "file") << "not a folder";
    const std::string underFile = (dir / "file" / "%04d.png").string();
    EXPECT_EQ(errorOf([&] { FrameWriter(underFile, 4, 4, 30.0); }).rfind(underFile + ": cannot create the folder", 0),
              0u);
}
