#include <mvcl/view/ImageIO.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

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

/// What an 8-bit sRGB file holds for a linear value, read back to linear (v × (1 / 255), as
/// OpenImageIO converts 8-bit values to float).
float throughEightBits(float linear) {
    return srgbToLinear(float(std::lround(linearToSrgb(linear) * 255.f)) * (1.f / 255.f));
}

/// Writes `f` to `p`, reads it back, and expects every channel to be `throughEightBits` of it.
void expectEightBitRoundTrip(const fs::path &p, const Framebuffer &f) {
    writeImage(p, f);
    const Framebuffer back = readImage(p);
    ASSERT_EQ(back.width(), f.width()) << p;
    ASSERT_EQ(back.height(), f.height()) << p;
    for (std::size_t i = 0; i < f.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(back.pixels()[i][c], throughEightBits(f.pixels()[i][c])) << p << " pixel " << i;
}

std::string errorOf(const auto &call) {
    try {
        call();
    } catch (const Error &e) {
        return e.what();
    }
    return "(no error)";
}

std::string firstBytes(const fs::path &p, std::size_t n) {
    std::ifstream in(p, std::ios::binary);
    std::string bytes(n, '\0');
    in.read(bytes.data(), std::streamsize(n));
    return bytes;
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
    EXPECT_EQ(firstBytes(p, 4), std::string("\x76\x2f\x31\x01", 4)); // OpenEXR's magic number
    const Framebuffer back = readImage(p);
    ASSERT_EQ(back.width(), 7);
    ASSERT_EQ(back.height(), 5);
    EXPECT_EQ(back.pixels(), f.pixels());
}

TEST(ImageIO, HdrKeepsLinearFloatsWithinItsSharedExponent) {
    Framebuffer f = gradient();
    f.at(0, 0) = {4.5f, 2.f, 1.f};
    const fs::path p = scratch("g.hdr");
    writeImage(p, f);
    EXPECT_EQ(firstBytes(p, 2), "#?");
    const Framebuffer back = readImage(p);
    ASSERT_EQ(back.width(), 7);
    ASSERT_EQ(back.height(), 5);
    // RGBE: 8 bits of mantissa under the largest channel's exponent.
    for (std::size_t i = 0; i < f.pixels().size(); ++i) {
        const glm::vec3 v = f.pixels()[i];
        const float largest = std::max({v.x, v.y, v.z});
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.pixels()[i][c], v[c], largest / 128.f) << "pixel " << i;
    }
    EXPECT_NEAR(back.at(0, 0).x, 4.5f, 0.04f);
}

TEST(ImageIO, PngIsSrgbEncodedEightBit) {
    const Framebuffer f = gradient();
    const fs::path p = scratch("g.png");
    writeImage(p, f);
    EXPECT_EQ(firstBytes(p, 8), "\x89PNG\r\n\x1a\n");
    const Framebuffer back = readImage(p);
    ASSERT_EQ(back.width(), 7);
    for (std::size_t i = 0; i < f.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(linearToSrgb(back.pixels()[i][c]), linearToSrgb(f.pixels()[i][c]), 0.5f / 255.f + 1e-6f);
}

// Encoding rounds each sRGB value to 8 bits; decoding is the sRGB curve of v × (1 / 255) (never a
// plain 2.2 gamma): the lossless 8-bit formats give exactly that back, the built-in ones and the
// OpenImageIO module alike.
TEST(ImageIO, LosslessEightBitFormatsReadBackTheEncodedValues) {
    expectEightBitRoundTrip(scratch("g.png"), gradient());
    expectEightBitRoundTrip(scratch("g.tga"), gradient());
    expectEightBitRoundTrip(scratch("g.bmp"), gradient());
    expectEightBitRoundTrip(scratch("G.PNG"), gradient()); // extensions in any case
    EXPECT_EQ(firstBytes(scratch("G.PNG"), 4), "\x89PNG");
    EXPECT_EQ(firstBytes(scratch("g.bmp"), 2), "BM");
}

TEST(ImageIO, JpgIsSrgbEncodedEightBitAndNearlyLossless) {
    const Framebuffer f = gradient();
    for (const char *name : {"g.jpg", "g.jpeg"}) {
        const fs::path p = scratch(name);
        writeImage(p, f);
        EXPECT_EQ(firstBytes(p, 3), "\xFF\xD8\xFF");
        const Framebuffer back = readImage(p);
        ASSERT_EQ(back.width(), 7);
        ASSERT_EQ(back.height(), 5);
        for (std::size_t i = 0; i < f.pixels().size(); ++i)
            for (int c = 0; c < 3; ++c) // quality 98, no chroma subsampling: a few steps of 255 at most
                EXPECT_NEAR(linearToSrgb(back.pixels()[i][c]), linearToSrgb(f.pixels()[i][c]), 4.f / 255.f) << name;
    }
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
    EXPECT_FALSE(fs::exists(scratch("x.unknownformat")));
    EXPECT_FALSE(fs::exists(scratch("x.unknownformat.part.unknownformat")));
}

TEST(ImageIO, ReadingTheWrongContentNamesTheFile) {
    for (const char *name : {"missing.exr", "missing.hdr", "missing.jpg"})
        EXPECT_NE(errorOf([&] { readImage(scratch(name)); }).find(name), std::string::npos) << name;
    // A PNG named .hdr or .exr is not read as one.
    writeImage(scratch("source.png"), gradient());
    fs::copy_file(scratch("source.png"), scratch("png-inside.hdr"), fs::copy_options::overwrite_existing);
    fs::copy_file(scratch("source.png"), scratch("png-inside.exr"), fs::copy_options::overwrite_existing);
    EXPECT_NE(errorOf([] { readImage(scratch("png-inside.hdr")); }).find("png-inside.hdr: cannot read image: not a Radiance HDR file"),
              std::string::npos);
    EXPECT_NE(errorOf([] { readImage(scratch("png-inside.exr")); }).find("png-inside.exr: cannot read image"), std::string::npos);
    // Garbage behind a PNG name.
    std::ofstream(scratch("garbage.png"), std::ios::binary) << "not an image at all";
    EXPECT_NE(errorOf([] { readImage(scratch("garbage.png")); }).find("garbage.png: cannot read image"), std::string::npos);
}

#ifdef MVCL_TEST_OIIO_MODULE
// .tif has no built-in codec: the OpenImageIO module writes and reads it, with the same 8-bit
// sRGB maths as the built-in 8-bit formats.
TEST(ImageIO, TifGoesThroughTheOpenImageIOModule) {
    const fs::path p = scratch("g.tif");
    expectEightBitRoundTrip(p, gradient());
    const std::string magic = firstBytes(p, 4);
    EXPECT_TRUE(magic == std::string("II*\0", 4) || magic == std::string("MM\0*", 4));
    EXPECT_FALSE(fs::exists(scratch("g.tif.part.tif")));
    // The module names what it cannot do, and the file.
    const std::string unknown = errorOf([] { writeImage(scratch("y.unknownformat"), gradient()); });
    EXPECT_NE(unknown.find("y.unknownformat: no image writer for this file type"), std::string::npos) << unknown;
    const std::string missing = errorOf([] { readImage(scratch("missing.tif")); });
    EXPECT_NE(missing.find("missing.tif: cannot read image"), std::string::npos) << missing;
}
#else
// Built without the module (MVCL_WITH_OIIO=OFF): a .tif fails, naming the module it needs.
TEST(ImageIO, TifWithoutTheModuleNamesIt) {
    fs::remove(scratch("no-module.tif"));
    const std::string error = errorOf([] { writeImage(scratch("no-module.tif"), gradient()); });
    EXPECT_NE(error.find("no-module.tif: the .tif format needs the OpenImageIO module mvcl-imageio-oiio"),
              std::string::npos)
        << error;
    EXPECT_FALSE(fs::exists(scratch("no-module.tif")));
}
#endif
