#pragma once
/// \file ImageModuleAbi_p.h
/// Private to ImageIO.cpp and the optional image module mvcl-imageio-oiio.so
/// (framework/imageio-oiio): the C interface between them. ImageIO dlopens the module the first
/// time a file needs it (.tif and every extension without a built-in codec) and calls its entry
/// point `mvcl_image_module`. Plain C types only: the module links OpenImageIO and nothing of
/// mvcl, and no exception or C++ object crosses the boundary.

#include <cstdint>

extern "C" {

#define MVCL_IMAGE_MODULE_SYMBOL "mvcl_image_module"
#define MVCL_IMAGE_MODULE_ABI 1u

struct MvclImageModule {
    std::uint32_t abiVersion; ///< MVCL_IMAGE_MODULE_ABI of the module's build
    std::uint32_t size;       ///< sizeof(MvclImageModule) of the module's build

    /// Writes width × height RGB pixels, 8 bits a channel, already sRGB-encoded, to `path`
    /// (the writer is picked by its extension). Returns nullptr, or what went wrong (valid until
    /// the module's next call on this thread).
    const char *(*write)(const char *path, int width, int height, const unsigned char *rgb);

    /// Reads `path` as RGB floats in [0, 1] as stored (8-bit values v become v × (1 / 255); no
    /// transfer function is undone): calls allocate(context, width, height) for a buffer of
    /// width × height × 3 floats and fills it. Returns nullptr, or what went wrong (as above).
    const char *(*read)(const char *path, void *context, float *(*allocate)(void *context, int width, int height));
};

typedef const MvclImageModule *(*MvclImageModuleEntry)();

} // extern "C"
