#include <mvcl/view/FrameWriter.h>

#include "ImageModule_p.h"
#include "VideoModule_p.h"

#include <mvcl/core/Error.h>
#include <mvcl/view/ImageIO.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <dlfcn.h>
#include <filesystem>
#include <unistd.h>
#include <vector>

namespace mvcl {

namespace fs = std::filesystem;

namespace {

constexpr const char *kVideoExtensions[] = {".mp4", ".mkv", ".mov"};

std::string loweredExtension(const std::string &target) {
    std::string ext = fs::path(target).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

/// The frame-number directive of a pattern: where it starts, its length and zero-padded width;
/// count = how many there are ("%%" is a literal percent sign).
struct FrameNumber {
    std::size_t start = std::string::npos, length = 0;
    int width = 0;
    int count = 0;
};

FrameNumber findFrameNumber(const std::string &pattern) {
    FrameNumber number;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') continue;
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        int width = 0;
        if (j < pattern.size() && pattern[j] == '0')
            for (++j; j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])); ++j)
                width = width * 10 + (pattern[j] - '0');
        if (j < pattern.size() && pattern[j] == 'd' && width <= 12) {
            if (number.count++ == 0) number = {i, j + 1 - i, width, 1};
        } else {
            number.count = -1; // some other directive: not a pattern of ours
            return number;
        }
        i = j;
    }
    return number;
}

/// The module that encodes videos, from the plugin search path, loaded once.
const MvclVideoModule &videoModule(const std::string &file) {
    static const MvclVideoModule *module = nullptr;
    if (!module) module = &detail::loadVideoModule(file, detail::imageModuleSearchPath());
    return *module;
}

/// Creates the folder `file` goes in and checks that files can be created there.
void checkWritableFolder(const std::string &target, const fs::path &file) {
    const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw Error(target, "cannot create the folder " + folder.string() + ": " + ec.message());
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw Error(target, "cannot write in the folder " + folder.string() + ": " + std::strerror(errno));
}

} // namespace

namespace detail {

const MvclVideoModule &loadVideoModule(const std::string &file, const std::vector<fs::path> &directories) {
    const std::string moduleFile = std::string(kFfmpegVideoModule) + ".so";
    std::string searched;
    const fs::path found = findModuleFile(moduleFile, directories, searched);
    const std::string needs = "a video needs the FFmpeg module " + moduleFile;
    if (found.empty())
        throw Error(file, needs + ", which was not found (looked in " + (searched.empty() ? "no folder" : searched) +
                              "; build mvcl with libavformat-dev, libavcodec-dev and libswscale-dev installed), "
                              "or write numbered images such as frames/%04d.png");
    void *handle = dlopen(found.c_str(), RTLD_NOW | RTLD_LOCAL); // FFmpeg's symbols stay local
    if (!handle) {
        const char *text = dlerror();
        throw Error(file, needs + ", which cannot be loaded: " + (text ? text : "unknown dynamic loader error"));
    }
    const auto entry = reinterpret_cast<MvclVideoModuleEntry>(dlsym(handle, MVCL_VIDEO_MODULE_SYMBOL));
    const MvclVideoModule *module = entry ? entry() : nullptr;
    if (!module || module->abiVersion != MVCL_VIDEO_MODULE_ABI || module->size != sizeof(MvclVideoModule)) {
        dlclose(handle);
        throw Error(file, needs + ", but " + found.string() + " was built for another version of mvcl (rebuild it)");
    }
    return *module;
}

} // namespace detail

struct FrameWriter::Private {
    std::string target;
    int width = 0, height = 0;
    const MvclVideoModule *video = nullptr;
    void *openVideo = nullptr;
    std::vector<unsigned char> rgb;
};

FrameWriter::FrameWriter(const std::string &target, int width, int height, double frameRate)
    : d(std::make_unique<Private>()) {
    d->target = target;
    d->width = width;
    d->height = height;
    if (!isVideo(target)) {
        const FrameNumber number = findFrameNumber(target);
        if (number.count != 1)
            throw Error(target, "numbered frames need one frame number in the name, such as frames/%04d.png "
                                "(or write a video: .mp4, .mkv, .mov)");
        checkWritableFolder(target, fs::path(frameFileName(target, 0)));
        return;
    }
    checkWritableFolder(target, fs::path(target));
    d->video = &videoModule(target);
    // The rate as a fraction, exact where a small denominator makes it so (12.5 = 25/2, 29.97 =
    // 2997/100), else in 1/1001ths as NTSC rates are.
    int denominator = 1001;
    for (const int candidate : {1, 2, 4, 5, 8, 10, 100, 1000})
        if (std::abs(frameRate * candidate - std::round(frameRate * candidate)) < 1e-6) {
            denominator = candidate;
            break;
        }
    const int numerator = int(std::lround(frameRate * denominator));
    const char *error = nullptr;
    d->openVideo = d->video->open(target.c_str(), width, height, numerator, denominator, &error);
    if (!d->openVideo) throw Error(target, error ? error : "cannot open the video");
}

FrameWriter::~FrameWriter() {
    if (d->openVideo) d->video->close(d->openVideo);
}

bool FrameWriter::isVideo(const std::string &target) {
    const std::string ext = loweredExtension(target);
    return std::ranges::find(kVideoExtensions, ext) != std::end(kVideoExtensions);
}

std::string FrameWriter::frameFileName(const std::string &pattern, int frame) {
    const FrameNumber number = findFrameNumber(pattern);
    if (number.start == std::string::npos) return pattern;
    char digits[32];
    std::snprintf(digits, sizeof digits, "%0*d", number.width, frame);
    std::string name;
    for (std::size_t i = 0; i < pattern.size(); ++i) { // "%%" before the number is one '%'
        if (i == number.start) {
            name += digits;
            i += number.length - 1;
        } else {
            name += pattern[i];
            if (pattern[i] == '%' && i + 1 < pattern.size() && pattern[i + 1] == '%') ++i;
        }
    }
    return name;
}

const std::string &FrameWriter::target() const { return d->target; }

bool FrameWriter::writesVideo() const { return d->video != nullptr; }

void FrameWriter::write(int frame, const Framebuffer &image) {
    if (image.width() != d->width || image.height() != d->height)
        throw Error(d->target, "frame " + std::to_string(frame) + " is " + std::to_string(image.width()) + "x" +
                                   std::to_string(image.height()) + ", not " + std::to_string(d->width) + "x" +
                                   std::to_string(d->height));
    if (!d->video) {
        writeImage(frameFileName(d->target, frame), image);
        return;
    }
    if (!d->openVideo) throw Error(d->target, "the video is finished");
    d->rgb.resize(image.pixels().size() * 3);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) // as writeImage encodes 8-bit files
            d->rgb[i * 3 + std::size_t(c)] = (unsigned char)std::lround(linearToSrgb(image.pixels()[i][c]) * 255.f);
    if (const char *error = d->video->write(d->openVideo, d->rgb.data())) throw Error(d->target, error);
}

void FrameWriter::finish() {
    if (!d->openVideo) return;
    const char *error = d->video->close(d->openVideo);
    d->openVideo = nullptr;
    if (error) throw Error(d->target, error);
}

} // namespace mvcl
