// WhittedIntegrator::plan: which stages a policy needs in a scene, and what forcing every stage
// would do instead. The images under both are compared in tests/view/SkipUnneededStagesTest.cpp.

#include <mvcl/tracer/IntegratorPlan.h>

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace mvcl;

namespace {

constexpr uint8_t kSecondaryRayTypes =
    rayTypeBit(RayType::Primary) | rayTypeBit(RayType::Reflection) | rayTypeBit(RayType::Refraction);

Material matte() {
    Material m;
    m.ambient = glm::vec3(0.f);
    m.diffuse = glm::vec3(0.7f);
    return m;
}

Light sun() {
    Light light;
    light.type = LightType::Directional;
    light.direction = {0.f, -1.f, 0.f};
    return light;
}

/// One sphere per layer 0..materials.size()-1, each with its own material, lit by a sun.
Scene layeredSpheres(const std::vector<Material> &materials) {
    Scene s;
    s.materials = materials;
    for (std::size_t i = 0; i < materials.size(); ++i)
        s.spheres.push_back({"sphere", {3.f * float(i), 0.f, 0.f}, 1.f, uint32_t(i), int(i)});
    s.lights.push_back(sun());
    return s;
}

IntegratorPlan planOf(const Scene &scene, const RayPolicy &policy, StageSelection selection) {
    const Tracer tracer(scene);
    return WhittedIntegrator(tracer).plan(policy, selection);
}

} // namespace

TEST(IntegratorPlan, OpaqueLitSceneCastsAnyHitShadowRaysAndNeedsNoSecondaryStage) {
    const Scene s = layeredSpheres({matte(), matte()});
    const IntegratorPlan plan = planOf(s, {}, StageSelection::SkipUnneeded);
    EXPECT_EQ(plan.shadows, ShadowStage::AnyHit);
    EXPECT_EQ(plan.forcedShadows, ShadowStage::AnyHit);
    EXPECT_EQ(plan.secondaryRayTypes, 0u);
    EXPECT_FALSE(plan.appliesColorMap);
}

TEST(IntegratorPlan, ForcingRunsEveryStageAsForASceneThatNeedsThemAll) {
    Material glass = matte();
    glass.transparency = 0.5f;
    const Scene s = layeredSpheres({matte(), glass});
    RayPolicy policy;
    policy.query(RayType::Shadow).layerMask = 0; // nothing casts
    policy.query(RayType::Primary).layerMask = layerBit(0);
    const IntegratorPlan plan = planOf(s, policy, StageSelection::ForceAll);
    EXPECT_EQ(plan.shadows, ShadowStage::TransparentWalk);
    EXPECT_EQ(plan.forcedShadows, ShadowStage::TransparentWalk);
    EXPECT_EQ(plan.secondaryRayTypes, kAllRayTypes);
    EXPECT_TRUE(plan.appliesColorMap);
}

TEST(IntegratorPlan, NoLightsOrShadowsOffMeanNoShadowStageEvenWhenForced) {
    Scene s = layeredSpheres({matte()});
    RayPolicy shadowsOff;
    shadowsOff.shading.shadows = false;
    for (const StageSelection selection : {StageSelection::SkipUnneeded, StageSelection::ForceAll}) {
        const IntegratorPlan plan = planOf(s, shadowsOff, selection);
        EXPECT_EQ(plan.shadows, ShadowStage::Off);
        EXPECT_EQ(plan.forcedShadows, ShadowStage::Off);
    }
    s.lights.clear();
    for (const StageSelection selection : {StageSelection::SkipUnneeded, StageSelection::ForceAll})
        EXPECT_EQ(planOf(s, {}, selection).shadows, ShadowStage::Off);
}

TEST(IntegratorPlan, ShadowMaskWithoutGeometryLeavesEveryLightUnoccluded) {
    Scene s = layeredSpheres({matte(), matte()});
    s.planes.push_back({"floor", {0.f, 1.f, 0.f}, -1.f, 0, 5});
    RayPolicy policy;
    for (const uint32_t mask : {0u, layerBit(2), layerBit(31) | layerBit(7)}) {
        policy.query(RayType::Shadow).layerMask = mask;
        const IntegratorPlan plan = planOf(s, policy, StageSelection::SkipUnneeded);
        EXPECT_EQ(plan.shadows, ShadowStage::Unoccluded) << mask;
        EXPECT_EQ(plan.forcedShadows, ShadowStage::AnyHit) << mask;
    }
    // Any layer with geometry in the mask may cast: a sphere's, a plane's.
    for (const uint32_t mask : {layerBit(1), layerBit(5), layerBit(0) | layerBit(2)}) {
        policy.query(RayType::Shadow).layerMask = mask;
        EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).shadows, ShadowStage::AnyHit) << mask;
    }
}

TEST(IntegratorPlan, MeshLayersCountAsTheTracerFilesThem) {
    Scene s;
    s.materials.push_back(matte());
    TriangleMesh mesh;
    mesh.positions = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}};
    mesh.indices = {{0, 1, 2}};
    mesh.layer = 40; // out of range: the tracer clamps it to 31
    s.meshes.push_back(mesh);
    s.lights.push_back(sun());
    RayPolicy policy;
    policy.query(RayType::Shadow).layerMask = layerBit(31);
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).shadows, ShadowStage::AnyHit);
    policy.query(RayType::Shadow).layerMask = ~layerBit(31);
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).shadows, ShadowStage::Unoccluded);
}

TEST(IntegratorPlan, EmptyShadowRangeLeavesTheLightUnoccluded) {
    const Scene s = layeredSpheres({matte()});
    RayPolicy policy;
    policy.query(RayType::Shadow).tMin = 2.f;
    policy.query(RayType::Shadow).tMax = 1.f;
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).shadows, ShadowStage::Unoccluded);
    // A NaN bound is not an empty range by that test: rays are cast as before.
    policy.query(RayType::Shadow).tMin = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).shadows, ShadowStage::AnyHit);
}

TEST(IntegratorPlan, ClipVolumesNeverMakeShadowRaysUnneeded) {
    // Even a keep-inside box far from all geometry leaves the rays cast: deciding from clip
    // volumes would need bounds on rounded hit points, and no lens makes such volumes today.
    const Scene s = layeredSpheres({matte()});
    RayPolicy policy;
    RayQuery &shadow = policy.query(RayType::Shadow);
    shadow.addClip(ClipVolume::box({100.f, 100.f, 100.f}, {101.f, 101.f, 101.f}, ClipVolume::Keep::Inside));
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).shadows, ShadowStage::AnyHit);
}

TEST(IntegratorPlan, TransparentWalkOnlyWhereACasterMayPassLight) {
    Material glass = matte();
    glass.transparency = 0.5f;
    const Scene s = layeredSpheres({matte(), glass});
    RayPolicy policy;
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).shadows, ShadowStage::TransparentWalk);
    policy.query(RayType::Shadow).layerMask = layerBit(0); // the glass casts no shadow
    const IntegratorPlan plan = planOf(s, policy, StageSelection::SkipUnneeded);
    EXPECT_EQ(plan.shadows, ShadowStage::AnyHit);
    EXPECT_EQ(plan.forcedShadows, ShadowStage::TransparentWalk);
}

TEST(IntegratorPlan, UnusedTransparentMaterialForcesTheWalkButIsNeverNeeded) {
    Material glass = matte();
    glass.transparency = 0.5f;
    Scene s = layeredSpheres({matte()});
    s.materials.push_back(glass); // in the table, on no geometry
    const IntegratorPlan plan = planOf(s, {}, StageSelection::SkipUnneeded);
    EXPECT_EQ(plan.shadows, ShadowStage::AnyHit);
    EXPECT_EQ(plan.forcedShadows, ShadowStage::TransparentWalk);
}

TEST(IntegratorPlan, NaNTransparencyOfACasterKeepsWhatForcingDoes) {
    // The walk multiplies by a NaN transparency where any-hit answers 0, so a caster with NaN
    // transparency keeps the walk whenever forcing walks.
    Material odd = matte();
    odd.transparency = std::numeric_limits<float>::quiet_NaN();
    Material glass = matte();
    glass.transparency = 0.5f;
    Scene s = layeredSpheres({odd});
    EXPECT_EQ(planOf(s, {}, StageSelection::SkipUnneeded).shadows, ShadowStage::AnyHit);
    EXPECT_EQ(planOf(s, {}, StageSelection::ForceAll).shadows, ShadowStage::AnyHit);
    s.materials.push_back(glass);
    EXPECT_EQ(planOf(s, {}, StageSelection::SkipUnneeded).shadows, ShadowStage::TransparentWalk);
}

TEST(IntegratorPlan, SecondaryStageOnlyForRayTypesThatMayHitAMirrorOrGlass) {
    Material mirror = matte();
    mirror.reflectivity = 0.8f;
    Material glass = matte();
    glass.transparency = 0.9f;
    const Scene s = layeredSpheres({matte(), mirror, glass});

    RayPolicy policy;
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).secondaryRayTypes, kSecondaryRayTypes);

    policy.query(RayType::Primary).layerMask = layerBit(0);    // sees only the matte sphere
    policy.query(RayType::Reflection).layerMask = layerBit(1); // mirrors see the mirror
    policy.query(RayType::Refraction).layerMask = layerBit(0);
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).secondaryRayTypes, rayTypeBit(RayType::Reflection));

    policy = RayPolicy{};
    policy.query(RayType::Primary).layerMask = layerBit(1);
    policy.shading.reflections = false; // the mirror no longer reflects
    policy.query(RayType::Reflection).layerMask = layerBit(2);
    policy.query(RayType::Refraction).layerMask = layerBit(0);
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).secondaryRayTypes, rayTypeBit(RayType::Reflection))
        << "glass reflects its Fresnel share even with reflections off";
    policy.shading.refractions = false;
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).secondaryRayTypes, 0u);

    policy = RayPolicy{};
    policy.shading.maxDepth = 0; // nothing bounces
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).secondaryRayTypes, 0u);
    policy.shading.maxDepth = 1;
    EXPECT_EQ(planOf(s, policy, StageSelection::SkipUnneeded).secondaryRayTypes, kSecondaryRayTypes);
}

TEST(IntegratorPlan, ColourMapOnlyWhereItIsNotTheIdentity) {
    const Scene s = layeredSpheres({matte()});
    RayPolicy policy;
    EXPECT_FALSE(planOf(s, policy, StageSelection::SkipUnneeded).appliesColorMap);
    policy.color.offset = glm::vec3(0.f, 0.f, 0.1f);
    EXPECT_TRUE(planOf(s, policy, StageSelection::SkipUnneeded).appliesColorMap);
}

TEST(IntegratorPlan, SkippedShadowRayIsCountedAndAddsTheFullLight) {
    const Scene s = layeredSpheres({matte(), matte()});
    const Tracer tracer(s);
    const WhittedIntegrator integrator(tracer);
    RayPolicy policy;
    policy.query(RayType::Shadow).layerMask = layerBit(4);
    const Ray down{{0.f, 3.f, 0.f}, {0.f, -1.f, 0.f}}; // onto the top of sphere 0, lit by the sun

    RayCounters skipping, forcing;
    const IntegratorPlan skip = integrator.plan(policy, StageSelection::SkipUnneeded);
    const IntegratorPlan force = integrator.plan(policy, StageSelection::ForceAll);
    const glm::vec3 skipped = integrator.radiance(down, policy, skip, skipping);
    const glm::vec3 forced = integrator.radiance(down, policy, force, forcing);
    EXPECT_EQ(skipped, forced);
    EXPECT_NEAR(skipped.r, 0.7f, 1e-5f);
    EXPECT_EQ(skipping.shadow, 0u);
    EXPECT_EQ(skipping.skippedShadowRays, 1u);
    EXPECT_EQ(skipping.skippedSecondaryChecks, 1u);
    EXPECT_EQ(skipping.skippedColorMaps, 1u);
    EXPECT_EQ(forcing.shadow, 1u);
    EXPECT_EQ(forcing.skippedShadowRays + forcing.skippedTransparentWalks + forcing.skippedSecondaryChecks +
                  forcing.skippedColorMaps,
              0u);
    // The overload without a plan plans the policy itself, skipping what is not needed.
    RayCounters planned;
    EXPECT_EQ(integrator.radiance(down, policy, planned), skipped);
    EXPECT_EQ(planned.skippedShadowRays, 1u);
}

TEST(IntegratorPlan, AnyHitInPlaceOfTheWalkIsCounted) {
    Material glass = matte();
    glass.transparency = 0.5f;
    Scene s = layeredSpheres({matte(), glass});
    s.spheres.push_back({"blocker", {0.f, 5.f, 0.f}, 1.f, 0, 0});
    const Tracer tracer(s);
    const WhittedIntegrator integrator(tracer);
    RayPolicy policy;
    policy.query(RayType::Shadow).layerMask = layerBit(0);
    const Ray down{{0.f, 3.f, 0.f}, {0.f, -1.f, 0.f}}; // below the blocker
    RayCounters skipping, forcing;
    const IntegratorPlan skip = integrator.plan(policy, StageSelection::SkipUnneeded);
    const IntegratorPlan force = integrator.plan(policy, StageSelection::ForceAll);
    const glm::vec3 skipped = integrator.radiance(down, policy, skip, skipping);
    const glm::vec3 forced = integrator.radiance(down, policy, force, forcing);
    EXPECT_EQ(skipped, forced);
    EXPECT_EQ(skipped, glm::vec3(0.f)); // in the blocker's shadow, no ambient
    EXPECT_EQ(skipping.shadow, 1u);
    EXPECT_EQ(skipping.skippedTransparentWalks, 1u);
    EXPECT_EQ(forcing.skippedTransparentWalks, 0u);
}

TEST(RayCounters, SkippedWorkIsSummedButIsNoRay) {
    RayCounters a;
    a.shadow = 2;
    a.skippedShadowRays = 3;
    a.skippedTransparentWalks = 4;
    a.skippedSecondaryChecks = 5;
    a.skippedColorMaps = 6;
    RayCounters sum;
    sum += a;
    sum += a;
    EXPECT_EQ(sum.total(), 4u);
    EXPECT_EQ(sum.skippedShadowRays, 6u);
    EXPECT_EQ(sum.skippedTransparentWalks, 8u);
    EXPECT_EQ(sum.skippedSecondaryChecks, 10u);
    EXPECT_EQ(sum.skippedColorMaps, 12u);
}
