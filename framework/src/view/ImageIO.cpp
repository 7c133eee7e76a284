#include <mvcl/view/ImageIO.h>

#include "ImageModule_p.h"

#include <mvcl/core/Error.h>
#include <mvcl/lens/LensRegistry.h>

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <string_view>
#include <vector>

// Where the image module lies relative to libmvcl.so's directory, in the build tree and once
// installed (set by framework/CMakeLists.txt from the plugin directories).
#ifndef MVCL_IMAGE_MODULE_DIR_FROM_BUILD_LIBDIR
#define MVCL_IMAGE_MODULE_DIR_FROM_BUILD_LIBDIR "mvcl/plugins"
#endif
#ifndef MVCL_IMAGE_MODULE_DIR_FROM_INSTALL_LIBDIR
#define MVCL_IMAGE_MODULE_DIR_FROM_INSTALL_LIBDIR "mvcl/plugins"
#endif

namespace mvcl {

namespace fs = std::filesystem;

namespace {

/// A framebuffer's pixels as a codec takes them: linear floats or sRGB-encoded bytes, RGB.
struct EncodedPixels {
    int width = 0;
    int height = 0;
    std::vector<float> linear;
    std::vector<unsigned char> srgb;
};

/// One built-in format. `write` returns "" or what went wrong; `read` throws mvcl::Error.
struct Codec {
    std::string_view extension; // lower case, with the dot
    bool linear;                // linear float (exr, hdr), else 8-bit sRGB
    std::string (*write)(const std::string &file, const EncodedPixels &pixels);
    Framebuffer (*read)(const std::string &file);
};

std::string writeFailure(const char *what) {
    const int error = errno;
    return std::string(what) + (error ? std::string(": ") + std::strerror(error) : std::string());
}

std::string writePng(const std::string &file, const EncodedPixels &p) {
    errno = 0;
    return stbi_write_png(file.c_str(), p.width, p.height, 3, p.srgb.data(), p.width * 3) ? "" : writeFailure("write failed");
}

std::string writeJpg(const std::string &file, const EncodedPixels &p) {
    errno = 0; // quality 98, as OpenImageIO wrote them
    return stbi_write_jpg(file.c_str(), p.width, p.height, 3, p.srgb.data(), 98) ? "" : writeFailure("write failed");
}

std::string writeTga(const std::string &file, const EncodedPixels &p) {
    errno = 0;
    return stbi_write_tga(file.c_str(), p.width, p.height, 3, p.srgb.data()) ? "" : writeFailure("write failed");
}

std::string writeBmp(const std::string &file, const EncodedPixels &p) {
    errno = 0;
    return stbi_write_bmp(file.c_str(), p.width, p.height, 3, p.srgb.data()) ? "" : writeFailure("write failed");
}

std::string writeHdr(const std::string &file, const EncodedPixels &p) {
    errno = 0;
    return stbi_write_hdr(file.c_str(), p.width, p.height, 3, p.linear.data()) ? "" : writeFailure("write failed");
}

std::string writeExr(const std::string &file, const EncodedPixels &p) {
    // One float plane per channel, in the order EXR lists channels (alphabetical: B, G, R).
    const std::size_t count = std::size_t(p.width) * std::size_t(p.height);
    std::vector<float> planes[3];
    for (int c = 0; c < 3; ++c) {
        planes[c].resize(count);
        for (std::size_t i = 0; i < count; ++i) planes[c][i] = p.linear[i * 3 + std::size_t(2 - c)];
    }
    float *planePointers[3] = {planes[0].data(), planes[1].data(), planes[2].data()};

    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = 3;
    image.images = reinterpret_cast<unsigned char **>(planePointers);
    image.width = p.width;
    image.height = p.height;

    EXRHeader header;
    InitEXRHeader(&header);
    EXRChannelInfo channels[3] = {};
    const char *names[3] = {"B", "G", "R"};
    for (int c = 0; c < 3; ++c) std::strcpy(channels[c].name, names[c]);
    int pixelTypes[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
    int storedTypes[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
    header.num_channels = 3;
    header.channels = channels;
    header.pixel_types = pixelTypes;
    header.requested_pixel_types = storedTypes;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

    const char *error = nullptr;
    if (SaveEXRImageToFile(&image, &header, file.c_str(), &error) == TINYEXR_SUCCESS) return "";
    std::string message = std::string("write failed: ") + (error ? error : "unknown OpenEXR error");
    if (error) FreeEXRErrorMessage(error);
    return message;
}

/// Opens a file for a reader; throws mvcl::Error naming it.
std::unique_ptr<std::FILE, int (*)(std::FILE *)> openForReading(const std::string &file) {
    std::unique_ptr<std::FILE, int (*)(std::FILE *)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
    if (!f) throw Error(file, std::string("cannot read image: ") + std::strerror(errno));
    return f;
}

/// png, jpg, tga, bmp: 8 (or 16, for PNG) bits of sRGB-encoded values, decoded to linear.
Framebuffer readSrgb(const std::string &file) {
    auto f = openForReading(file);
    if (stbi_is_hdr_from_file(f.get())) throw Error(file, "cannot read image: a Radiance HDR file (name it .hdr)");
    const bool sixteenBits = stbi_is_16_bit_from_file(f.get());
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<void, void (*)(void *)> data(sixteenBits ? static_cast<void *>(stbi_load_from_file_16(f.get(), &width, &height, &channels, 3))
                                                             : static_cast<void *>(stbi_load_from_file(f.get(), &width, &height, &channels, 3)),
                                                 &stbi_image_free);
    if (!data) throw Error(file, std::string("cannot read image: ") + stbi_failure_reason());
    Framebuffer image(width, height);
    // v × (1 / max), bit for bit the values OpenImageIO gave mvcl for 8- and 16-bit files.
    const float scale = sixteenBits ? 1.f / 65535.f : 1.f / 255.f;
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const std::size_t k = i * 3 + std::size_t(c);
            const float v = sixteenBits ? float(static_cast<const stbi_us *>(data.get())[k])
                                        : float(static_cast<const stbi_uc *>(data.get())[k]);
            image.pixels()[i][c] = srgbToLinear(v * scale);
        }
    return image;
}

Framebuffer readHdr(const std::string &file) {
    auto f = openForReading(file);
    // stbi_loadf would take an 8-bit image too, with a gamma of its own: refuse those.
    if (!stbi_is_hdr_from_file(f.get())) throw Error(file, "cannot read image: not a Radiance HDR file");
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, void (*)(void *)> data(stbi_loadf_from_file(f.get(), &width, &height, &channels, 3), &stbi_image_free);
    if (!data) throw Error(file, std::string("cannot read image: ") + stbi_failure_reason());
    Framebuffer image(width, height);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels()[i][c] = data.get()[i * 3 + std::size_t(c)];
    return image;
}

Framebuffer readExr(const std::string &file) {
    openForReading(file); // a missing file is named as the other readers name it
    float *rgba = nullptr;
    int width = 0, height = 0;
    const char *error = nullptr;
    if (LoadEXR(&rgba, &width, &height, file.c_str(), &error) != TINYEXR_SUCCESS) {
        const std::string message = std::string("cannot read image: ") + (error ? error : "unknown OpenEXR error");
        if (error) FreeEXRErrorMessage(error);
        throw Error(file, message);
    }
    std::unique_ptr<float, void (*)(void *)> data(rgba, &std::free);
    Framebuffer image(width, height);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels()[i][c] = data.get()[i * 4 + std::size_t(c)];
    return image;
}

/// The built-in codecs. Every other extension (.tif, ...) goes to the OpenImageIO module.
constexpr Codec kCodecs[] = {
    {".png", false, writePng, readSrgb}, {".jpg", false, writeJpg, readSrgb},  {".jpeg", false, writeJpg, readSrgb},
    {".tga", false, writeTga, readSrgb}, {".bmp", false, writeBmp, readSrgb},  {".hdr", true, writeHdr, readHdr},
    {".exr", true, writeExr, readExr},
};

std::string lowerCaseExtension(const fs::path &path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

const Codec *builtInCodec(const fs::path &path) {
    const std::string ext = lowerCaseExtension(path);
    for (const Codec &codec : kCodecs)
        if (codec.extension == ext) return &codec;
    return nullptr;
}

/// The module, loaded the first time a file needs it. A failed load is not remembered: the
/// next file tries again (and names the problem again).
const MvclImageModule &oiioModule(const std::string &file) {
    static std::mutex mutex;
    static const MvclImageModule *module = nullptr;
    const std::lock_guard<std::mutex> lock(mutex);
    if (!module) module = &detail::loadImageModule(file, detail::imageModuleSearchPath());
    return *module;
}

/// The module's allocate callback: a buffer of width × height RGB floats.
struct ModuleReadBuffer {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;
};

float *allocateModuleBuffer(void *context, int width, int height) {
    auto *buffer = static_cast<ModuleReadBuffer *>(context);
    try {
        buffer->width = width;
        buffer->height = height;
        buffer->rgb.assign(std::size_t(width) * std::size_t(height) * 3, 0.f);
        return buffer->rgb.data();
    } catch (const std::bad_alloc &) {
        return nullptr;
    }
}

char anchor; // an address inside libmvcl.so, for dladdr

} // namespace

namespace detail {

std::vector<fs::path> imageModuleSearchPath() {
    std::vector<fs::path> directories = LensRegistry::defaultSearchPath();
    Dl_info info;
    if (dladdr(&anchor, &info) && info.dli_fname) {
        std::error_code ec;
        const fs::path libraryDir = fs::absolute(info.dli_fname, ec).parent_path();
        if (!ec)
            for (const char *relative : {MVCL_IMAGE_MODULE_DIR_FROM_BUILD_LIBDIR, MVCL_IMAGE_MODULE_DIR_FROM_INSTALL_LIBDIR}) {
                const fs::path directory = (libraryDir / relative).lexically_normal();
                if (std::find(directories.begin(), directories.end(), directory) == directories.end())
                    directories.push_back(directory);
            }
    }
    return directories;
}

fs::path findModuleFile(const std::string &moduleFile, const std::vector<fs::path> &directories, std::string &searched) {
    for (const fs::path &directory : directories) {
        std::error_code ec;
        if (fs::is_regular_file(directory / moduleFile, ec)) return fs::absolute(directory / moduleFile, ec);
        searched += (searched.empty() ? "" : ", ") + directory.string();
    }
    return {};
}

const MvclImageModule &loadImageModule(const std::string &file, const std::vector<fs::path> &directories) {
    const std::string moduleFile = std::string(kOiioImageModule) + ".so";
    const std::string ext = fs::path(file).extension().string();
    const std::string format = ext.empty() ? "a file without an extension" : "the " + ext + " format";
    std::string searched;
    const fs::path found = findModuleFile(moduleFile, directories, searched);
    if (found.empty())
        throw Error(file, format + " needs the OpenImageIO module " + kOiioImageModule + " (" + moduleFile +
                              "), which was not found (looked in " + (searched.empty() ? "no directory" : searched) +
                              "); built-in formats: .png, .jpg, .exr, .hdr, .tga, .bmp");
    // Local: OpenImageIO's symbols stay out of the global scope. Never closed.
    void *handle = dlopen(found.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char *text = dlerror();
        throw Error(file, format + " needs the OpenImageIO module " + kOiioImageModule + ", which cannot be loaded: " +
                              (text ? text : "unknown dynamic loader error"));
    }
    const auto entry = reinterpret_cast<MvclImageModuleEntry>(dlsym(handle, MVCL_IMAGE_MODULE_SYMBOL));
    const MvclImageModule *module = entry ? entry() : nullptr;
    if (!module || module->abiVersion != MVCL_IMAGE_MODULE_ABI || module->size != sizeof(MvclImageModule)) {
        dlclose(handle);
        throw Error(file, format + " needs the OpenImageIO module " + kOiioImageModule + ", but " + found.string() +
                              " was built for another version of mvcl (rebuild it)");
    }
    return *module;
}

} // namespace detail

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
    const Codec *codec = builtInCodec(path);
    // Before anything is created: a missing module fails without a trace on disk.
    const MvclImageModule *module = codec ? nullptr : &oiioModule(name);
    if (path.has_parent_path()) {
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) throw Error(name, "cannot create folder: " + ec.message());
    }
    if (image.width() <= 0 || image.height() <= 0) throw Error(name, "cannot write an image without pixels");
    if (std::size_t(image.width()) * std::size_t(image.height()) > std::size_t(INT_MAX / 4))
        throw Error(name, "cannot write an image this large");

    EncodedPixels pixels;
    pixels.width = image.width();
    pixels.height = image.height();
    const bool linear = codec && codec->linear;
    if (linear) {
        pixels.linear.resize(image.pixels().size() * 3);
        for (std::size_t i = 0; i < image.pixels().size(); ++i)
            for (int c = 0; c < 3; ++c) pixels.linear[i * 3 + std::size_t(c)] = image.pixels()[i][c];
    } else {
        pixels.srgb.resize(image.pixels().size() * 3);
        for (std::size_t i = 0; i < image.pixels().size(); ++i)
            for (int c = 0; c < 3; ++c)
                pixels.srgb[i * 3 + std::size_t(c)] = (unsigned char)std::lround(linearToSrgb(image.pixels()[i][c]) * 255.f);
    }

    // Write to a temporary file and rename, so a failed write never destroys an older image.
    // The temporary name keeps the extension: the module picks its writer by it.
    const std::string temp = name + ".part" + path.extension().string();
    std::string problem;
    if (codec) {
        problem = codec->write(temp, pixels);
    } else if (const char *error = module->write(temp.c_str(), pixels.width, pixels.height, pixels.srgb.data())) {
        problem = error;
    }
    std::error_code ec;
    if (!problem.empty()) {
        std::filesystem::remove(temp, ec);
        throw Error(name, problem);
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) throw Error(name, "cannot replace the file: " + ec.message());
}

Framebuffer readImage(const std::filesystem::path &path) {
    const std::string name = path.string();
    if (const Codec *codec = builtInCodec(path)) return codec->read(name);
    const MvclImageModule &module = oiioModule(name);
    ModuleReadBuffer buffer;
    if (const char *error = module.read(name.c_str(), &buffer, &allocateModuleBuffer)) throw Error(name, error);
    Framebuffer image(buffer.width, buffer.height);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels()[i][c] = srgbToLinear(buffer.rgb[i * 3 + std::size_t(c)]);
    return image;
}

} // namespace mvcl
