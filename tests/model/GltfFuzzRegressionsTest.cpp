/// Every input in tests/data/fuzz-regressions/ once crashed (or broke an invariant of) the glTF
/// loader under scripts/ci-fuzz.sh. Each must now load or be rejected with an mvcl::Error naming
/// it; a crash fails the test run, and under scripts/ci-sanitizers.sh so does any memory error.

#include <mvcl/core/Error.h>
#include <mvcl/model/GltfLoader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace mvcl;

namespace {

namespace fs = std::filesystem;

const fs::path kRegressions = fs::path(MVCL_TEST_DATA_DIR) / "fuzz-regressions";

std::vector<fs::path> regressionInputs() {
    std::vector<fs::path> inputs;
    for (const fs::directory_entry &e : fs::directory_iterator(kRegressions))
        if (e.is_regular_file() && e.path().filename() != "README.md") inputs.push_back(e.path());
    std::sort(inputs.begin(), inputs.end());
    return inputs;
}

TEST(GltfFuzzRegressions, EveryInputLoadsOrIsRejectedCleanly) {
    const std::vector<fs::path> inputs = regressionInputs();
    ASSERT_FALSE(inputs.empty()) << kRegressions;
    for (const fs::path &input : inputs) {
        SCOPED_TRACE(input.filename().string());
        std::ifstream in(input, std::ios::binary);
        const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string name = input.filename().string();
        // As the fuzzer saw it: from memory, no asset folder.
        try {
            const Scene scene = loadGltfFromMemory(bytes, name, "");
            EXPECT_FALSE(scene.materials.empty());
        } catch (const Error &e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
}

} // namespace
