#include <mvcl/model/LayerContact.h>

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mvcl {
namespace {

TEST(LayerContact, OffByDefault) {
    const LayerContact contact;
    EXPECT_FALSE(contact.isEnabled());
    Bounds3f b;
    b.expand(glm::vec3(0.f));
    b.expand(glm::vec3(3.f, 4.f, 0.f));
    EXPECT_EQ(contact.sceneUnits(b), 0.f);
    EXPECT_EQ(contact.toString(), "0");
}

TEST(LayerContact, RelativeToTheSceneSizeOrInSceneUnits) {
    Bounds3f b;
    b.expand(glm::vec3(0.f));
    b.expand(glm::vec3(3.f, 4.f, 0.f)); // diagonal 5
    const LayerContact relative = LayerContact::parse("1e-3");
    EXPECT_EQ(relative.measure, LayerContact::Measure::RelativeToSceneSize);
    EXPECT_FLOAT_EQ(relative.sceneUnits(b), 5e-3f);
    const LayerContact units = LayerContact::parse("0.25units");
    EXPECT_EQ(units.measure, LayerContact::Measure::SceneUnits);
    EXPECT_FLOAT_EQ(units.sceneUnits(b), 0.25f);
    EXPECT_EQ(LayerContact::parse("0.25 units"), units);
    EXPECT_EQ(LayerContact::parse(units.toString()), units);
    EXPECT_EQ(LayerContact::parse(relative.toString()), relative);
    EXPECT_EQ(relative.sceneUnits(Bounds3f{}), 0.f); // empty scene
}

TEST(LayerContact, BadTextIsRefusedWithTheReason) {
    for (const char *text : {"", "abc", "-1e-3", "1e-3 mm", "inf", "nan", "1e999"}) {
        try {
            LayerContact::parse(text);
            ADD_FAILURE() << "accepted '" << text << "'";
        } catch (const Error &e) {
            EXPECT_NE(std::string(e.what()).find("layer contact"), std::string::npos) << e.what();
        }
    }
}

} // namespace
} // namespace mvcl
