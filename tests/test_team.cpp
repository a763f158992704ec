// The render loop under a team of several ranks, run in-process (thread_team.h): what mpirun's
// tests check end to end (test_distributed.cpp), here cheap enough to check in detail.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "core/error.h"
#include "scenes/builtin_scenes.h"
#include "integrators/render.h"
#include "thread_team.h"

namespace tripath {
namespace {

RenderResult renderOnTeam(const Scene& scene, const Integrator& integrator, RenderSettings settings, int ranks) {
    if (ranks == 1) return render(scene, integrator, settings);
    std::optional<RenderResult> rank0;
    test::ThreadTeam(ranks).run([&](Team& team, int rank) {
        RenderSettings mine = settings;
        mine.team = &team;
        mine.threads = 1;
        RenderResult r = render(scene, integrator, mine);
        if (rank == 0) rank0.emplace(std::move(r));
    });
    return std::move(*rank0);
}

// Catches: a rank rendering a block another renders too, or none; a reduction that loses a rank.
TEST(Team, RanksThatAreThreadsGiveTheOneProcessImage) {
    const Scene scene(builtinScene("cornell-spheres"), 24, 20);
    const auto integrator = makeIntegrator("bdpt", {});
    RenderSettings settings;
    settings.spp = 10;  // three blocks, the last one short
    const Image one = render(scene, *integrator, settings).image();
    for (int ranks : {2, 3}) {
        const RenderResult r = renderOnTeam(scene, *integrator, settings, ranks);
        EXPECT_EQ(r.passes, 10) << ranks;
        EXPECT_EQ(r.image().rgb, one.rgb) << ranks << " ranks";
    }
}

// Drops a NaN sample at two pixels of every pass: pixel 20 (x = 20, so the second 16-pixel tile
// of a 32-pixel row) and pixel 32 + pass mod 4 (row 1, the first tile). One process logs a pass's
// drops in tile order, so the second comes first although its pixel index is larger.
class NanAtTwoPixels final : public PixelSampleIntegrator {
public:
    NanAtTwoPixels() : PixelSampleIntegrator({}) {}
    std::string name() const override { return "nan-at-two-pixels"; }
    StrategySet strategies() const override { return {.maxS = 1, .minT = 2}; }  // pt's
    void sample(const Scene&, const Pass& pass, int pixel, const CameraRay&, SampleStream&, PathBuffers&,
                ContributionSink& sink) const override {
        if (pixel != 20 && pixel != 32 + int(pass.index % 4)) return;
        Connection c;
        c.unweighted = Spectrum(std::nanf(""));
        c.weight = 1;
        sink.add(Strategy{0, 2}, c);
    }
};

// The log printed at the end of a render names the team's first drops, the ones a single process
// meets first. Catches: rank 0 printing its own log (under 2 ranks it would hold passes 8 and 9,
// which it rendered, instead of 4 to 7), logs merged by pixel index instead of tile order, and a
// log longer than kDroppedLogSize.
TEST(DroppedSamples, TheTeamLogsTheFirstOnesAsOneProcessWould) {
    const Scene scene(builtinScene("cornell"), 32, 32);
    const NanAtTwoPixels integrator;
    RenderSettings settings;
    settings.spp = 10;
    std::vector<std::pair<uint64_t, int>> expected;
    for (uint64_t pass = 0; expected.size() < kDroppedLogSize; ++pass) {
        expected.emplace_back(pass, 32 + int(pass % 4));
        expected.emplace_back(pass, 20);
    }
    for (int ranks : {1, 2, 3}) {
        const RenderResult r = renderOnTeam(scene, integrator, settings, ranks);
        EXPECT_EQ(r.droppedSamples, 20u) << ranks;
        std::vector<std::pair<uint64_t, int>> logged;
        for (const DroppedSample& d : r.droppedLog) logged.emplace_back(d.pass, d.pixel);
        EXPECT_EQ(logged, expected) << ranks << " ranks";
    }
}

// A check that fails on some ranks fails on all of them, with the lowest failing rank's words.
// Catches: a rank that returns while others throw (it would wait alone in its next collective),
// the highest failing rank's message instead of the lowest's, and rank 0's message given a prefix.
TEST(Team, TogetherEndsEveryRankWithTheLowestFailingRanksMessage) {
    for (const std::vector<int>& failing : std::vector<std::vector<int>>{{}, {2}, {1, 2}, {0, 2}}) {
        std::vector<std::string> seen(3);
        test::ThreadTeam(3).run([&](Team& team, int rank) {
            try {
                together(team, [&] {
                    if (std::find(failing.begin(), failing.end(), rank) != failing.end())
                        throw InputError("no such file on rank " + std::to_string(rank));
                });
                seen[size_t(rank)] = "ok";
            } catch (const InputError& e) {
                seen[size_t(rank)] = e.what();
            }
        });
        const std::string expected = failing.empty()   ? "ok"
                                     : failing[0] == 0 ? "no such file on rank 0"
                                                       : fmt::format("rank {0}: no such file on rank {0}", failing[0]);
        for (const std::string& s : seen) EXPECT_EQ(s, expected) << "failing ranks " << failing.size();
    }
}

// Catches: gathered bytes out of rank order, and a broadcast that leaves a rank with its own bytes.
TEST(Team, BytesAreBroadcastFromRankZeroAndGatheredInRankOrder) {
    std::vector<std::string> received(3);
    std::vector<std::string> gathered;
    test::ThreadTeam(3).run([&](Team& team, int rank) {
        std::string bytes = "from " + std::to_string(rank);
        team.broadcast(bytes);
        received[size_t(rank)] = bytes;
        std::vector<std::string> all = team.gather(std::string(size_t(rank) + 1, char('a' + rank)));
        if (rank == 0) gathered = all;
        else EXPECT_TRUE(all.empty());
    });
    EXPECT_EQ(received, std::vector<std::string>(3, "from 0"));
    EXPECT_EQ(gathered, (std::vector<std::string>{"a", "bb", "ccc"}));
}

}  // namespace
}  // namespace tripath
