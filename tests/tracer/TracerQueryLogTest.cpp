// TracerQueryLog: what a frame bench replays must be the frame's own queries, each once, with
// their ranges, and the replay must answer as the tracer answered them.

#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/TracerQueryLog.h>
#include <mvcl/tracer/WhittedIntegrator.h>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <array>
#include <bit>

using namespace mvcl;

namespace {

Ray rayThrough(float x, float y) {
    const glm::vec3 eye(0.5f, 3.6f, 7.5f);
    return Ray{eye, glm::normalize(glm::vec3(-2.f + 4.f * x, 2.f * y, 0.f) - eye)};
}

} // namespace

TEST(TracerQueryLog, RecordsEachPublicQueryOnceAndReplaysTheSameAnswers) {
    const Scene scene = makeBuiltinScene("cube-in-cube");
    Tracer tracer(scene);
    TracerQueryLog log;
    tracer.setQueryLog(&log);

    RayQuery layered;
    RayQuery shortRange;
    shortRange.tMin = 0.5f;
    shortRange.tMax = 3.f;
    shortRange.layerMask = 0b1;
    std::array<Ray, Tracer::kPacketSize> rays;
    for (int i = 0; i < Tracer::kPacketSize; ++i) rays[size_t(i)] = rayThrough(float(i % 4) / 3.f, float(i / 4) / 3.f);
    std::array<Hit, Tracer::kPacketSize> hits;
    std::array<float, Tracer::kPacketSize> ends;
    ends.fill(4.f);
    std::size_t expected = 0;
    Hit hit;
    expected += tracer.closestHit(rays[0], layered, hit);
    expected += tracer.closestHit(rays[5], shortRange, hit);
    expected += tracer.anyHit(rays[3], layered, 2.f);
    // Packets are one call each, also where the tracer answers them ray by ray inside.
    expected += std::size_t(std::popcount(tracer.closestHits(rays, layered, hits)));
    expected += std::size_t(std::popcount(tracer.anyHits(rays, shortRange, ends)));
    tracer.setQueryLog(nullptr);
    tracer.closestHit(rays[1], layered, hit); // not recorded

    EXPECT_EQ(log.calls(), 5u);
    EXPECT_EQ(log.closestHitRays(), 2u + Tracer::kPacketSize);
    EXPECT_EQ(log.anyHitRays(), 1u + Tracer::kPacketSize);
    EXPECT_EQ(log.distinctQueries(), 2u); // two masks; the ranges are kept per call
    EXPECT_GT(expected, 0u);
    EXPECT_EQ(log.replay(tracer, 0, log.calls()), expected);
    EXPECT_EQ(log.replay(tracer, 0, 2) + log.replay(tracer, 2, 99), expected);
    log.clear();
    EXPECT_EQ(log.calls(), 0u);
}

TEST(TracerQueryLog, AFrameRecordsAsManyRaysAsItCounts) {
    // Opaque occluders only (every stage any-hit): each counted ray is one recorded ray.
    Scene scene = makeBuiltinScene("onion");
    Tracer tracer(scene);
    const WhittedIntegrator integrator(tracer);
    TracerQueryLog log;
    tracer.setQueryLog(&log);
    RayCounters counters;
    const RayPolicy policy;
    for (int i = 0; i < 64; ++i)
        integrator.radiance(Ray{{0.f, 2.2f, 4.f}, glm::normalize(glm::vec3(float(i % 8) / 8.f - 0.5f, float(i / 8) / 8.f - 0.8f, -1.f))},
                            policy, counters);
    tracer.setQueryLog(nullptr);
    EXPECT_EQ(log.closestHitRays() + log.anyHitRays(), counters.total());
    EXPECT_EQ(log.anyHitRays(), counters.shadow);
}
