/// libFuzzer harness for lens-stack (session) files, parseLensStackJson with the in-tree lens
/// plugins: every input must end in a description or an mvcl::Error naming the file and the JSON
/// path; and a description that reads must write (lensStackJson) and read back equal to itself,
/// as the viewer's save and reopen rely on. Anything else is a finding.
///
/// The plugins are loaded once from the build's plugin folder (<exe>/../lib/mvcl/plugins).

#include <mvcl/core/Error.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/lens/LensRegistry.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace {

const mvcl::LensRegistry &registry() {
    static const mvcl::LensRegistry *const loaded = [] {
        auto *r = new mvcl::LensRegistry;
        r->loadModules(mvcl::LensRegistry::defaultSearchPath());
        if (r->lensTypes().empty()) {
            // Without lens types every file with a lens fails the same way: no coverage.
            std::fprintf(stderr, "mvcl-fuzz-session: no lens plugins found next to the harness\n");
            std::abort();
        }
        return r;
    }();
    return *loaded;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char *>(data), size);
    mvcl::LensStackDescription description;
    try {
        description = mvcl::parseLensStackJson(text, "fuzz.json", registry());
    } catch (const mvcl::Error &) {
        return 0;
    }
    std::string written;
    try {
        written = mvcl::lensStackJson(description);
    } catch (const mvcl::Error &) {
        return 0; // e.g. a label that is not UTF-8: refused when written, with a message
    }
    const mvcl::LensStackDescription again = mvcl::parseLensStackJson(written, "fuzz-written.json", registry());
    if (!(again == description)) {
        std::fprintf(stderr, "written and read back, the session differs:\n%s\n", written.c_str());
        std::abort();
    }
    return 0;
}
