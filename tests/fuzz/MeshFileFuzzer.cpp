/// libFuzzer harness for the mesh-file readers (OBJ, STL, PLY): every input must end in a Scene
/// or an mvcl::Error, and a Scene must keep the invariants the tracer relies on.
///
/// Built once per format (tests/fuzz/CMakeLists.txt, MVCL_FUZZ_FORMAT = Obj, Stl or Ply). The
/// input is handed to that format's reader whatever it holds, as a misnamed file would be.
/// loadMeshFileFromMemory reads no material libraries, so the fuzzer never reads the disk.

#include <mvcl/core/Error.h>
#include <mvcl/model/MeshFileLoader.h>

#include "SceneInvariants.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    mvcl::MeshFileOptions options;
    options.maxFileBytes = 1u << 20;
    options.maxTriangles = 1u << 20; // a hostile count must fail, not allocate gigabytes
    try {
        mvcl::fuzz::checkSceneInvariants(
            mvcl::loadMeshFileFromMemory({data, size}, "fuzz", mvcl::MeshFormat::MVCL_FUZZ_FORMAT, options));
    } catch (const mvcl::Error &) {
        // A clean rejection.
    }
    return 0;
}
