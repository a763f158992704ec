// A render's memory before it runs out (docs/design.md §5, docs/memory.md): the estimate's parts
// against what their structures hold, the refusal of a render over its budget before any pass,
// what the machine has as /proc and the cgroup files say it, and sizes as text. The estimate's
// accuracy against measured peak memory is docs/memory.md's table, not a test: resident memory
// depends on the allocator and the machine.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/available_memory.h"
#include "core/byte_size.h"
#include "core/error.h"
#include "integrators/light_phase.h"
#include "requests/memory_check.h"
#include "support.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

uint64_t partBytes(const MemoryEstimate& e, const std::string& name) {
    for (const MemoryPart& p : e.parts)
        if (p.name == name) return p.bytes;
    return 0;
}

MemoryEstimate estimateOf(const RenderRequest& r) {
    const Scene scene(builtinScene(r.scene.empty() ? "cornell" : r.scene), r.width, r.height);
    return estimateMemory(scene, *makeIntegrator(r.integrator, integratorSettings(r)), renderSettings(r));
}

// The film keeps, per pixel of each of its images, the block's three doubles and three 192-bit
// exact totals: 3 × (8 + 24) = 96 bytes. pt with --depth-images at max-depth 3 and strategy
// layers up to k = 2 keeps 1 + 3 + 2 × 3 images: pt's strategies of k ≤ 2 are (0, 2), (0, 3) and
// (1, 2), each weighted and unweighted. Fails if the film's part leaves out its layers or
// miscounts its bytes a pixel.
TEST(Memory, TheFilmTakesNinetySixBytesAPixelOfEachImage) {
    RenderRequest r = test::smallRequest();
    r.width = 40;
    r.height = 24;
    EXPECT_EQ(partBytes(estimateOf(r), "film"), 96u * 40 * 24);
    r.maxDepth = 3;
    r.depthImages = true;
    r.strategyImages = 2;
    EXPECT_EQ(partBytes(estimateOf(r), "film"), 10u * 96 * 40 * 24);
}

// pt holds nothing that grows with the image but its film and the image it writes out, so the
// estimate grows by those per pixel added and by nothing else. Fails if a part of the estimate
// does not follow the image size, or another one does.
TEST(Memory, ThePathTracersEstimateGrowsByTheFilmAndTheImageOut) {
    RenderRequest r = test::smallRequest();
    r.width = r.height = 32;
    const uint64_t small = estimateOf(r).total();
    r.width = r.height = 96;
    const uint64_t large = estimateOf(r).total();
    EXPECT_EQ(large - small, (96 + kOutputBytesPerPixel) * (96u * 96 - 32u * 32));
}

// With no more light paths than it traces, the survey sees every path of the pass: its mean
// vertices, BSDF parameters and mergeable vertices times the path count are what the pass's store
// holds, counted path by path (sky's textured ground keeps parameters beside its vertices).
// Fails if the survey traced other paths than the pass (other streams, another walk), counted its
// vertices otherwise than the merge search takes them, or missed the kept parameters.
TEST(Memory, TheSurveyCountsWhatThePassStores) {
    for (const char* scene : {"cornell", "cornell-spheres", "sky"}) {
        RenderRequest r = test::smallRequest();
        r.integrator = "vcm";
        r.lightPaths = 3000;
        r.lightPathsGiven = true;
        const Scene built(builtinScene(scene), 16, 16);
        const auto integrator = makeIntegrator(r.integrator, integratorSettings(r));
        const uint64_t pass = 5, seed = 7;
        const PixelSampleIntegrator& samples = *integrator->pixelSamples();
        const LightPathSurvey survey = LightPhase::survey(built, samples, pass, {seed, StreamDomain::CameraSample});
        LightPhase phase;
        phase.run(built, samples, pass, {seed, StreamDomain::CameraSample});
        size_t mergeable = 0, bsdfs = 0;
        for (size_t i = 0; i < phase.store().paths(); ++i) {
            const SubpathView path = phase.store().path(i);
            for (size_t j = 1; j < path.size(); ++j) mergeable += !path[j].delta;
            bsdfs += path.bsdfs.size();
        }
        EXPECT_NEAR(survey.vertices * 3000, double(phase.store().vertices()), 1e-6) << scene;
        EXPECT_NEAR(survey.bsdfs * 3000, double(bsdfs), 1e-6) << scene;
        if (std::string(scene) == "sky") EXPECT_GT(bsdfs, 0u);
        EXPECT_NEAR(survey.mergeable * 3000, double(mergeable), 1e-6) << scene;
    }
}

// A render over its budget is refused in one line before its first pass, naming the estimate and
// the budget; with the budget raised it renders. Fails if the check comes after the film or the
// light phase, or not at all.
TEST(Memory, ARenderOverItsBudgetIsRefusedBeforeItsFirstPass) {
    RenderRequest r = test::smallRequest();
    r.integrator = "vcm";
    r.memoryLimit = uint64_t(64) << 20;
    r.memoryLimitGiven = true;
    const Scene scene(builtinScene("cornell"), r.width, r.height);
    const auto integrator = makeIntegrator(r.integrator, integratorSettings(r));
    RenderSettings settings = renderSettings(r);
    int passes = 0;
    settings.progress = [&](int, double) { ++passes; };
    try {
        render(scene, *integrator, settings);
        ADD_FAILURE() << "rendered over a budget of 64 MiB";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("the render needs an estimated"), std::string::npos) << m;
        EXPECT_NE(m.find("--memory-limit is 64.0 MiB"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    EXPECT_EQ(passes, 0);
    r.memoryLimit = uint64_t(64) << 30;
    settings = renderSettings(r);
    settings.progress = [&](int, double) { ++passes; };
    const RenderResult result = render(scene, *integrator, settings);
    EXPECT_EQ(passes, r.spp);
    EXPECT_EQ(result.memory.total(), estimateMemory(scene, *integrator, settings).total());
}

// The refusal names the flags that shrink the parts that weigh, as the front end spells them:
// light paths are one per pixel by default, so the image size and --light-paths both shrink them.
// When the process and the scene alone exceed the budget, it says so instead.
TEST(Memory, TheRefusalSaysWhatToLowerInTheFrontEndsSpelling) {
    RenderRequest r = test::smallRequest();
    r.integrator = "vcm";
    r.width = r.height = 256;
    const MemoryEstimate e = estimateOf(r);
    auto refusal = [&](Spelling spelling, uint64_t budget = 0) {
        try {
            requireMemory(e, budget > 0 ? budget : e.total() - 1, spelling);
        } catch (const InputError& x) {
            return std::string(x.what());
        }
        return std::string("accepted");
    };
    EXPECT_NE(refusal(Spelling::CommandLine).find("lower --width/--height or --light-paths, or raise --memory-limit"),
              std::string::npos)
        << refusal(Spelling::CommandLine);
    EXPECT_NE(refusal(Spelling::Python).find("lower width/height or light_paths, or raise memory_limit"), std::string::npos)
        << refusal(Spelling::Python);
    EXPECT_NE(refusal(Spelling::CommandLine, 1024).find("but --memory-limit is 1.00 KiB: the process and its scene alone take 140 MiB"),
              std::string::npos)
        << refusal(Spelling::CommandLine, 1024);
}

// A tree of the files availableMemory() reads, under a folder of its own.
class MachineFiles : public testing::Test {
protected:
    void SetUp() override {
        root_ = fs::temp_directory_path() / ("tripath-memory-" + std::to_string(getpid()));
        fs::remove_all(root_);
        write("proc/meminfo", "MemTotal:       16000000 kB\nMemFree:         1000 kB\nMemAvailable:    8000000 kB\n");
        write("proc/self/status", "Name:\ttripath\nVmPeak:\t  999999 kB\nVmRSS:\t  100000 kB\n");
    }
    void TearDown() override { fs::remove_all(root_); }
    void write(const std::string& file, const std::string& text) {
        fs::create_directories((root_ / file).parent_path());
        std::ofstream(root_ / file) << text;
    }
    fs::path root_;
};

// Without a control group's limit: resident memory plus MemAvailable.
TEST_F(MachineFiles, WithoutALimitTheMachineHasItsAvailableMemory) {
    write("proc/self/cgroup", "0::/job\n");
    write("sys/fs/cgroup/job/memory.max", "max\n");
    write("sys/fs/cgroup/job/memory.current", "5000000000\n");
    const auto m = availableMemory(root_);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->bytes, (uint64_t(100000) + 8000000) * 1024);
    EXPECT_EQ(m->limitBy, "MemAvailable");
}

// A version 2 group's limit, less what the group uses but its inactive page cache, binds when
// smaller; its parent's smaller one binds tighter.
TEST_F(MachineFiles, AVersionTwoGroupsLimitBindsWhenSmaller) {
    write("proc/self/cgroup", "0::/batch/job\n");
    write("sys/fs/cgroup/batch/job/memory.max", "4000000000\n");
    write("sys/fs/cgroup/batch/job/memory.current", "1500000000\n");
    write("sys/fs/cgroup/batch/job/memory.stat", "anon 1000000000\ninactive_file 500000000\nactive_file 1\n");
    auto m = availableMemory(root_);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->bytes, uint64_t(100000) * 1024 + 3000000000u);
    EXPECT_EQ(m->limitBy, "cgroup memory.max");
    write("sys/fs/cgroup/batch/memory.max", "2000000000\n");
    write("sys/fs/cgroup/batch/memory.current", "1500000000\n");
    m = availableMemory(root_);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->bytes, uint64_t(100000) * 1024 + 500000000u);
}

// Version 1: the memory controller's line, limit_in_bytes and usage_in_bytes; its "no limit" (2^63
// rounded to a page) is none.
TEST_F(MachineFiles, AVersionOneGroupsLimitBindsWhenSmaller) {
    write("proc/self/cgroup", "5:cpu,cpuacct:/x\n4:memory:/slurm/job1\n");
    write("sys/fs/cgroup/memory/slurm/job1/memory.limit_in_bytes", "3000000000\n");
    write("sys/fs/cgroup/memory/slurm/job1/memory.usage_in_bytes", "1000000000\n");
    write("sys/fs/cgroup/memory/slurm/memory.limit_in_bytes", "9223372036854771712\n");
    write("sys/fs/cgroup/memory/slurm/memory.usage_in_bytes", "1000000000\n");
    const auto m = availableMemory(root_);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->bytes, uint64_t(100000) * 1024 + 2000000000u);
    EXPECT_EQ(m->limitBy, "cgroup memory.limit_in_bytes");
}

TEST_F(MachineFiles, NothingIsKnownWithoutProc) {
    fs::remove(root_ / "proc/meminfo");
    EXPECT_FALSE(availableMemory(root_));
}

TEST(ByteSize, SizesReadInPowersOf1024) {
    EXPECT_EQ(parseByteSize("4096"), 4096u);
    EXPECT_EQ(parseByteSize("8G"), uint64_t(8) << 30);
    EXPECT_EQ(parseByteSize("8gb"), uint64_t(8) << 30);
    EXPECT_EQ(parseByteSize("8GiB"), uint64_t(8) << 30);
    EXPECT_EQ(parseByteSize("512m"), uint64_t(512) << 20);
    EXPECT_EQ(parseByteSize("1.5T"), uint64_t(3) << 39);
    EXPECT_EQ(parseByteSize("2k"), 2048u);
    for (const char* bad : {"", "G", "-1G", "8 G", "8X", "8GiBs", "1e3", ".5G", "5.G", "99999999999T"})
        EXPECT_FALSE(parseByteSize(bad)) << bad;
}

TEST(ByteSize, AmountsWrittenWithThreeFigures) {
    EXPECT_EQ(bytesText(512), "512 B");
    EXPECT_EQ(bytesText(96 * 1024), "96.0 KiB");
    EXPECT_EQ(bytesText(uint64_t(3) << 30), "3.00 GiB");
    EXPECT_EQ(bytesText(uint64_t(1500) << 20), "1.46 GiB");
    EXPECT_EQ(bytesText(uint64_t(200) << 40), "200 TiB");
}

}  // namespace
}  // namespace tripath
