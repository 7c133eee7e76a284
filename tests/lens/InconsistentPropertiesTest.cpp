// Property combinations that make no sense are rejected with a message naming the lens and the
// problem, and leave the committed snapshot as it was: a reversed box when it is set, a clip
// volume that cannot exist when the lens commits. Nothing silently renders as "no effect".

#include <mvcl/core/Error.h>
#include <mvcl/lens/LensRegistry.h>
#include <mvcl/testing/ErrorOf.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

namespace mvcl {
namespace {

using test::errorOf;

std::shared_ptr<Lens> clipLens() {
    static LensRegistry registry;
    if (!registry.contains("clip")) registry.loadModule(std::filesystem::path(MVCL_PLUGIN_BUILD_DIR) / "mvcl-lens-clip.so");
    return registry.create("clip");
}

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

TEST(InconsistentProperties, AReversedBoxIsRejectedNamingTheLensThePropertyAndTheAxis) {
    const std::shared_ptr<Lens> clip = clipLens();
    const Box3d defaultBox = clip->property("box").toBox3();
    const std::string message = errorOf([&] { clip->setPropertyText("box", "1,0,0,0,1,1"); });
    EXPECT_TRUE(contains(message, "lens 'clip'")) << message;
    EXPECT_TRUE(contains(message, "box")) << message;
    EXPECT_TRUE(contains(message, "minimum exceeds its maximum on x")) << message;
    EXPECT_EQ(clip->property("box").toBox3(), defaultBox) << "the staged value stays as it was";
}

TEST(InconsistentProperties, AHalfSpaceWithoutANormalIsRejectedAtCommitAndTheSnapshotStays) {
    const std::shared_ptr<Lens> clip = clipLens();
    clip->setPropertyText("volume", "halfSpace");
    clip->commit();
    const auto committed = clip->snapshot();
    clip->setPropertyText("planeNormal", "0,0,0"); // a valid vector3 on its own
    const std::string message = errorOf([&] { clip->commit(); });
    EXPECT_TRUE(contains(message, "lens 'clip'")) << message;
    EXPECT_TRUE(contains(message, "zero normal")) << message;
    EXPECT_EQ(clip->snapshot(), committed) << "a failed commit keeps the previous snapshot";
}

} // namespace
} // namespace mvcl
