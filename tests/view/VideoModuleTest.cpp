// How FrameWriter finds the optional FFmpeg module mvcl-video-ffmpeg.so (view/VideoModule_p.h),
// and what it says when the module is missing or broken. Internal: the loader is not exported.

#include "view/VideoModule_p.h"

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace mvcl;
namespace fs = std::filesystem;

namespace {

fs::path emptyDirectory(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-video-module-test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string loadError(const std::string &file, const std::vector<fs::path> &directories) {
    try {
        detail::loadVideoModule(file, directories);
    } catch (const Error &e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(VideoModule, AMissingEncoderIsOneLineNamingTheFileAndTheWayOut) {
    const fs::path dir = emptyDirectory("none");
    const std::string error = loadError("out/clip.mp4", {dir});
    EXPECT_EQ(error, "out/clip.mp4: a video needs the FFmpeg module mvcl-video-ffmpeg.so, which was not found "
                     "(looked in " + dir.string() +
                         "; build mvcl with libavformat-dev, libavcodec-dev and libswscale-dev installed), or write "
                         "numbered images such as frames/%04d.png");
}

TEST(VideoModule, AFileThatIsNotTheModuleIsNamed) {
    const fs::path dir = emptyDirectory("broken");
    std::ofstream(dir / "mvcl-video-ffmpeg.so") << "not a shared library";
    const std::string error = loadError("clip.mp4", {dir});
    EXPECT_EQ(error.rfind("clip.mp4: a video needs the FFmpeg module mvcl-video-ffmpeg.so, which cannot be loaded", 0),
              0u)
        << error;
}

#ifdef MVCL_TEST_FFMPEG_MODULE
TEST(VideoModule, TheBuiltModuleLoadsWithThisInterface) {
    const MvclVideoModule &module = detail::loadVideoModule("clip.mp4", {fs::path(MVCL_PLUGIN_BUILD_DIR)});
    EXPECT_EQ(module.abiVersion, MVCL_VIDEO_MODULE_ABI);
    EXPECT_EQ(module.size, sizeof(MvclVideoModule));
    EXPECT_NE(module.open, nullptr);
}
#endif
