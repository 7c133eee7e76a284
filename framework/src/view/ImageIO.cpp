#include <mvcl/view/ImageIO.h>

#include <mvcl/core/Error.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace mvcl {

namespace {

bool isFloatFormat(const std::filesystem::path &path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".exr" || ext == ".hdr";
}

} // namespace

float linearToSrgb(float v) {
    if (!(v > 0.f)) return 0.f;
    if (v >= 1.f) return 1.f;
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

float srgbToLinear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

void writeImage(const std::filesystem::path &path, const Framebuffer &image) {
    const std::string name = path.string();
    if (path.has_parent_path()) {
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) throw Error(name, "cannot create folder: " + ec.message());
    }
    auto out = OIIO::ImageOutput::create(name);
    if (!out) throw Error(name, "no image writer for this file type (use .png, .jpg, .tif, .exr)");

    const bool linear = isFloatFormat(path);
    OIIO::ImageSpec spec(image.width(), image.height(), 3,
                         linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", linear ? "Linear" : "sRGB");
    spec.attribute("Software", "mvcl");
    // Write to a temporary file and rename, so a failed write never destroys an older image.
    const std::string temp = name + ".part" + path.extension().string();
    if (!out->open(temp, spec)) throw Error(name, "cannot open for writing: " + out->geterror());
    bool ok;
    if (linear) {
        std::vector<float> data(image.pixels().size() * 3);
        for (std::size_t i = 0; i < image.pixels().size(); ++i)
            for (int c = 0; c < 3; ++c) data[i * 3 + c] = image.pixels()[i][c];
        ok = out->write_image(OIIO::TypeDesc::FLOAT, data.data());
    } else {
        std::vector<unsigned char> data(image.pixels().size() * 3);
        for (std::size_t i = 0; i < image.pixels().size(); ++i)
            for (int c = 0; c < 3; ++c)
                data[i * 3 + c] = (unsigned char)std::lround(linearToSrgb(image.pixels()[i][c]) * 255.f);
        ok = out->write_image(OIIO::TypeDesc::UINT8, data.data());
    }
    ok = out->close() && ok;
    if (!ok) {
        std::filesystem::remove(temp);
        throw Error(name, "write failed: " + out->geterror());
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) throw Error(name, "cannot replace the file: " + ec.message());
}

Framebuffer readImage(const std::filesystem::path &path) {
    const std::string name = path.string();
    auto in = OIIO::ImageInput::open(name);
    if (!in) throw Error(name, "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec &spec = in->spec();
    const bool linear = isFloatFormat(path);
    std::vector<float> data(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
        throw Error(name, "cannot read image: " + in->geterror());
    Framebuffer image(spec.width, spec.height);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = data[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
            image.pixels()[i][c] = linear ? v : srgbToLinear(v);
        }
    return image;
}

} // namespace mvcl
