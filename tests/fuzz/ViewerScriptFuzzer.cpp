/// libFuzzer harness for mvcl-viewer's script reader (--script FILE, apps/viewer/ViewerScript.cpp):
/// every input must end in a script or an mvcl::Error naming the line, and every argument of a
/// read script must give a number, a whole number or a word, or that error. Anything else is a
/// finding. The reader is compiled into the harness (it needs no window).

#include "ViewerScript.h"

#include <mvcl/core/Error.h>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    std::istringstream text(std::string(reinterpret_cast<const char *>(data), size));
    try {
        mvcl::viewer::ViewerScript script = mvcl::viewer::ViewerScript::parse(text, "fuzz.txt");
        for (; !script.isFinished(); script.advance()) {
            const mvcl::viewer::ScriptCommand &command = script.current();
            for (std::size_t i = 0; i <= command.args.size(); ++i) {
                try {
                    (void)command.number(i);
                } catch (const mvcl::Error &) {
                }
                try {
                    (void)command.integer(i);
                } catch (const mvcl::Error &) {
                }
                try {
                    (void)command.word(i);
                } catch (const mvcl::Error &) {
                }
            }
        }
    } catch (const mvcl::Error &) {
    }
    return 0;
}
