#include <mvcl/view/ImageIO.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <filesystem>

using namespace mvcl;
namespace fs = std::filesystem;

namespace {

Framebuffer gradient() {
    Framebuffer f(7, 5);
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x) f.at(x, y) = {float(x) / 6.f, float(y) / 4.f, 0.25f};
    return f;
}

fs::path scratch(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-imageio-test";
    fs::create_directories(dir);
    return dir / name;
}

} // namespace

TEST(ImageIO, SrgbTransferRoundTrips) {
    for (float v : {0.f, 0.001f, 0.0031308f, 0.18f, 0.5f, 1.f})
        EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-6f);
    EXPECT_EQ(linearToSrgb(-1.f), 0.f);
    EXPECT_EQ(linearToSrgb(5.f), 1.f);
}

TEST(ImageIO, ExrKeepsLinearFloatsExactly) {
    Framebuffer f = gradient();
    f.at(0, 0) = {4.5f, 0.f, 1e-4f}; // over-range and tiny values survive in EXR
    const fs::path p = scratch("g.exr");
    writeImage(p, f);
    const Framebuffer back = readImage(p);
    ASSERT_EQ(back.width(), 7);
    ASSERT_EQ(back.height(), 5);
    EXPECT_EQ(back.pixels(), f.pixels());
}

TEST(ImageIO, PngIsSrgbEncodedEightBit) {
    const Framebuffer f = gradient();
    const fs::path p = scratch("g.png");
    writeImage(p, f);
    const Framebuffer back = readImage(p);
    ASSERT_EQ(back.width(), 7);
    for (std::size_t i = 0; i < f.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(linearToSrgb(back.pixels()[i][c]), linearToSrgb(f.pixels()[i][c]), 0.5f / 255.f + 1e-6f);
}

TEST(ImageIO, ErrorsNameTheFileAndKeepTheOldImage) {
    const fs::path p = scratch("keep.png");
    writeImage(p, gradient());
    const auto before = fs::file_size(p);
    EXPECT_THROW(writeImage(scratch("x.unknownformat"), gradient()), Error);
    try {
        readImage(scratch("missing.png"));
        FAIL();
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos);
    }
    EXPECT_EQ(fs::file_size(p), before);
}
