// mvcl-imageio-oiio.so: the image formats that mvcl has no built-in codec for (.tif and any
// other extension OpenImageIO knows), loaded by ImageIO.cpp only when such a file is written or
// read. It keeps OpenImageIO, and the ~260 libraries it pulls in, off every process's start-up.
// The interface is ImageModuleAbi_p.h.

#include "ImageModuleAbi_p.h"

#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace {

thread_local std::string g_lastError;

const char *fail(std::string message) {
    g_lastError = std::move(message);
    return g_lastError.c_str();
}

const char *writeImage(const char *path, int width, int height, const unsigned char *rgb) {
    try {
        auto out = OIIO::ImageOutput::create(path);
        if (!out) {
            OIIO::geterror(); // clear OpenImageIO's pending message
            return fail("no image writer for this file type (use .png, .jpg, .exr, .hdr, .tif, .tga, .bmp)");
        }
        OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        spec.attribute("Software", "mvcl");
        if (!out->open(path, spec)) return fail("cannot open for writing: " + out->geterror());
        bool ok = out->write_image(OIIO::TypeDesc::UINT8, rgb);
        ok = out->close() && ok;
        if (!ok) return fail("write failed: " + out->geterror());
        return nullptr;
    } catch (const std::exception &e) {
        return fail(std::string("write failed: ") + e.what());
    }
}

const char *readImage(const char *path, void *context, float *(*allocate)(void *, int, int)) {
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in) return fail("cannot read image: " + OIIO::geterror());
        const OIIO::ImageSpec &spec = in->spec();
        if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 1) return fail("cannot read image: it has no pixels");
        const std::size_t count = std::size_t(spec.width) * std::size_t(spec.height);
        std::vector<float> data(count * std::size_t(spec.nchannels));
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
            return fail("cannot read image: " + in->geterror());
        float *rgb = allocate(context, spec.width, spec.height);
        if (!rgb) return fail("cannot read image: it does not fit in memory");
        // Grey and grey + alpha become grey RGB, as the built-in codecs read them; alpha is dropped.
        const std::size_t channels = std::size_t(spec.nchannels);
        for (std::size_t i = 0; i < count; ++i)
            for (std::size_t c = 0; c < 3; ++c) rgb[i * 3 + c] = data[i * channels + (channels < 3 ? 0 : c)];
        return nullptr;
    } catch (const std::bad_alloc &) {
        return fail("cannot read image: it does not fit in memory");
    } catch (const std::exception &e) {
        return fail(std::string("cannot read image: ") + e.what());
    }
}

const MvclImageModule kModule{MVCL_IMAGE_MODULE_ABI, sizeof(MvclImageModule), writeImage, readImage};

} // namespace

extern "C" __attribute__((visibility("default"))) const MvclImageModule *mvcl_image_module() { return &kModule; }
