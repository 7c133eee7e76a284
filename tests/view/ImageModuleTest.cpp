// How ImageIO finds the optional OpenImageIO module mvcl-imageio-oiio.so (view/ImageModule_p.h),
// and what it says when the module is missing or broken. Internal: the loader is not exported.

#include "view/ImageModule_p.h"

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

using namespace mvcl;
namespace fs = std::filesystem;

namespace {

fs::path emptyDirectory(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-image-module-test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string loadError(const std::string &file, const std::vector<fs::path> &directories) {
    try {
        detail::loadImageModule(file, directories);
    } catch (const Error &e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(ImageModule, AMissingModuleIsNamedWithWhereItWasLookedFor) {
    const fs::path dir = emptyDirectory("none");
    const std::string error = loadError("out/picture.tif", {dir});
    EXPECT_NE(error.find("out/picture.tif: the .tif format needs the OpenImageIO module mvcl-imageio-oiio "
                         "(mvcl-imageio-oiio.so), which was not found (looked in " +
                         dir.string() + ")"),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("built-in formats: .png, .jpg, .exr, .hdr, .tga, .bmp"), std::string::npos) << error;
    EXPECT_NE(loadError("picture", {}).find("picture: a file without an extension needs the OpenImageIO module "
                                            "mvcl-imageio-oiio"),
              std::string::npos);
}

TEST(ImageModule, AFileThatIsNotTheModuleIsNamed) {
    const fs::path dir = emptyDirectory("broken");
    std::ofstream(dir / "mvcl-imageio-oiio.so") << "not a shared library";
    const std::string error = loadError("x.tif", {dir});
    EXPECT_NE(error.find("x.tif: the .tif format needs the OpenImageIO module mvcl-imageio-oiio, which cannot be loaded"),
              std::string::npos)
        << error;
}

TEST(ImageModule, TheSearchPathEndsWithThePluginFolders) {
    const std::vector<fs::path> path = detail::imageModuleSearchPath();
    const fs::path exeDir = fs::read_symlink("/proc/self/exe").parent_path();
    const fs::path besideExe = (exeDir / ".." / "lib" / "mvcl" / "plugins").lexically_normal();
    EXPECT_NE(std::find(path.begin(), path.end(), exeDir), path.end());
    EXPECT_NE(std::find(path.begin(), path.end(), besideExe), path.end());
}

#ifdef MVCL_TEST_OIIO_MODULE
TEST(ImageModule, TheBuiltModuleLoadsWithThisInterface) {
    const MvclImageModule &module = detail::loadImageModule("x.tif", {fs::path(MVCL_PLUGIN_BUILD_DIR)});
    EXPECT_EQ(module.abiVersion, MVCL_IMAGE_MODULE_ABI);
    EXPECT_EQ(module.size, sizeof(MvclImageModule));
    EXPECT_NE(module.write, nullptr);
    EXPECT_NE(module.read, nullptr);
}
#endif
