/// libFuzzer harness for session files, with the in-tree lens plugins: as a lens-stack file
/// (parseLensStackJson) and as a session of several views (parseSessionJson: version 2, or 1 read
/// as one view). Every input must end in a description or an mvcl::Error naming the file and the
/// JSON path; a description that reads must write and read back the same (lensStackJson: equal
/// descriptions; sessionJson: the same text written twice), as the viewer's save and reopen rely
/// on. Anything else is a finding.
///
/// The plugins are loaded once from the build's plugin folder (<exe>/../lib/mvcl/plugins).

#include <mvcl/core/Error.h>
#include <mvcl/io/LensStackFile.h>
#include <mvcl/io/SessionFile.h>
#include <mvcl/lens/LensRegistry.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
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

/// The session reading: what it writes reads back and writes the same text again.
void checkSession(std::string_view text) {
    std::string written;
    try {
        written = mvcl::sessionJson(mvcl::parseSessionJson(text, "fuzz.json", registry()));
    } catch (const mvcl::Error &) {
        return;
    }
    const std::string again = mvcl::sessionJson(mvcl::parseSessionJson(written, "fuzz-written.json", registry()));
    if (again != written) {
        std::fprintf(stderr, "written and read back, the session writes differently:\n%s\n---\n%s\n", written.c_str(),
                     again.c_str());
        std::abort();
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char *>(data), size);
    checkSession(text);
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
