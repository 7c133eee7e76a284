/// libFuzzer harness for the glTF loader, "load → triangles" (catalogue case 37): every input must
/// end in a Scene or an mvcl::Error. Anything else (a crash, a sanitizer report, another exception
/// type, or a Scene that breaks the invariants the tracer relies on) is a finding.
///
/// Built twice (tests/fuzz/CMakeLists.txt): MVCL_FUZZ_GLB=0 fuzzes ASCII .gltf, MVCL_FUZZ_GLB=1
/// binary .glb. Each rejects the other's inputs, so that its corpus stays its own format.
/// No asset folder is given, so external files are refused and the fuzzer never reads the disk.

#include <mvcl/core/Error.h>
#include <mvcl/model/GltfLoader.h>

#include "SceneInvariants.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace {

bool isGlb(const std::uint8_t *data, std::size_t size) { return size >= 4 && std::memcmp(data, "glTF", 4) == 0; }

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    if (isGlb(data, size) != bool(MVCL_FUZZ_GLB)) return -1; // not this entry point's format
    mvcl::GltfLoadOptions options;
    options.maxFileBytes = 1u << 20; // keep single inputs cheap; libFuzzer's -max_len is smaller anyway
    try {
        mvcl::fuzz::checkSceneInvariants(mvcl::loadGltfFromMemory({data, size}, MVCL_FUZZ_GLB ? "fuzz.glb" : "fuzz.gltf", "",
                                                      options));
    } catch (const mvcl::Error &) {
        // A clean rejection: the expected outcome for almost every input.
    }
    return 0;
}
