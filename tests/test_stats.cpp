// The render's own accounting (core/stats.h, `--stats`): counts that a missing, doubled or
// lost increment would change, and phase samples that land where the time goes.
#include <gtest/gtest.h>

#include <array>
#include <utility>

#include "support.h"

namespace tripath::test {
namespace {

TEST(Stats, OneClosestHitRayPerCameraSampleAtPathLengthOne) {
    // At --max-depth 1 a camera walk is the sensor and one hit: exactly one ray per sample, no
    // BSDF sampled, no next-event estimation (its paths have k >= 2), no shadow ray.
    RenderRequest r = test::smallRequest();
    r.maxDepth = 1;
    r.spp = 3;
    const Scene scene(builtinScene("cornell"), r.width, r.height);
    const StatsSnapshot s = renderScene(scene, r).stats;
    EXPECT_EQ(s[Event::ClosestHitRays], uint64_t(r.width) * r.height * r.spp);
    EXPECT_EQ(s[Event::ShadowRays], 0u);
    EXPECT_EQ(s[Event::BsdfSamples], 0u);
    EXPECT_EQ(s[Event::EmitterSamples], 0u);
    EXPECT_GT(s[Event::EmitterHits], 0u);  // the ceiling light is in view
}

TEST(Stats, CountsAreTheSameWhateverTheThreadCount) {
    // Counts are of events the seed determines; a thread whose counts no snapshot sees (a task
    // that never enrolled) would lose some of them on more threads.
    RenderRequest r = test::smallRequest();
    r.width = r.height = 32;
    r.spp = 2;
    const Scene spheres(builtinScene("cornell-spheres"), r.width, r.height), sky(builtinScene("sky"), r.width, r.height);
    std::array<uint64_t, kEventCount> seen{};
    // vcm on a scene with glass and a mirror does every kind of event but mlt's chains' steps,
    // which mlt does, and the derivations of textured BSDFs, which the sky's checkered ground
    // asks for: none is left unwired.
    const std::pair<const char*, const Scene*> runs[] = {{"vcm", &spheres}, {"mlt", &spheres}, {"vcm", &sky}};
    for (const auto& [integrator, scene] : runs) {
        r.integrator = integrator;
        r.threads = 1;
        const StatsSnapshot one = renderScene(*scene, r).stats;
        r.threads = 2;
        const StatsSnapshot two = renderScene(*scene, r).stats;
        for (int i = 0; i < kEventCount; ++i) {
            const auto e = static_cast<Event>(i);
            EXPECT_EQ(one[e], two[e]) << integrator << " on " << scene->name() << ": " << eventName(e);
            seen[size_t(i)] += one[e];
        }
    }
    for (int i = 0; i < kEventCount; ++i) EXPECT_GT(seen[size_t(i)], 0u) << eventName(static_cast<Event>(i));
}

TEST(Stats, PhasesAreSampledOnlyWhenAskedAndWhereTheWorkIs) {
    RenderRequest r = test::smallRequest();
    r.width = r.height = 64;
    r.spp = 0;
    const Scene scene(builtinScene("cornell"), r.width, r.height);
    const auto integrator = makeIntegrator("bdpt", IntegratorSettings{});
    RenderSettings rs;
    rs.spp = 0;
    rs.seconds = 1.0;
    const RenderResult off = render(scene, *integrator, rs);
    for (uint64_t n : off.stats.phaseSamples) EXPECT_EQ(n, 0u);
    rs.timing = true;
    const RenderResult on = render(scene, *integrator, rs);
    // A second of CPU time gives ~100 profiling ticks per core at the coarsest kernel tick; bdpt
    // spends most of it in its tiles of camera samples and about a sixth in tracing its light
    // paths, so no sample in either would be a (5/6)^100 accident: the tags are not being set.
    // bdpt does not merge: nothing may be tagged as the merge index.
    const auto& samples = on.stats.phaseSamples;
    uint64_t working = 0;
    for (int i = 0; i < kPhaseCount; ++i)
        if (static_cast<Phase>(i) != Phase::Idle) working += samples[i];
    EXPECT_GT(working, 50u);
    EXPECT_GT(samples[static_cast<int>(Phase::CameraSamples)], samples[static_cast<int>(Phase::LightPaths)]);
    EXPECT_GT(samples[static_cast<int>(Phase::LightPaths)], 0u);
    EXPECT_EQ(samples[static_cast<int>(Phase::MergeIndex)], 0u);
    EXPECT_FALSE(timingEnabled());  // the render turned the profiler off again
}

}  // namespace
}  // namespace tripath::test
