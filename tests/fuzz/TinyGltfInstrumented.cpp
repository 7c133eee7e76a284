// tinygltf's implementation, compiled with the harness's instrumentation (see CMakeLists.txt).
// Image decoding stays out: the loader installs its own no-op image loader.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
