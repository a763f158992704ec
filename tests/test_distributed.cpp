// Distributed rendering, end to end through the built binary under Open MPI's mpirun
// (apps/processes.h, render.h): N ranks give the EXR one process gives, bit for bit; a checkpointed
// render cut off and resumed (on another rank count) gives the uninterrupted one; a rank that
// cannot read the scene or that is killed ends the job with a non-zero exit, and the last
// checkpoint stays loadable. Ranks are oversubscribed on CI's two cores.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "image/image.h"
#include "shell_test.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

// mpirun refuses root unless told; CI runs as root.
const std::string kMpirun = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 300 '" TRIPATH_MPIEXEC
                            "' --oversubscribe";
const std::string kTripath = std::string("'") + TRIPATH_BINARY + "'";

class Distributed : public test::ShellTest {
protected:
    // Every mpirun makes its session directory under one shared folder (/tmp/ompi.<host>.<uid>)
    // and removes the folder when it ends; two jobs starting and ending at once (ctest -j2 runs
    // two of these tests side by side) can race there, and the loser fails in orte_init with
    // "mkdir ... File exists". So each test's jobs get a folder of their own, kept short:
    // PMIx puts its sockets in it, and a socket's path must fit in 108 bytes.
    void SetUp() override {
        ShellTest::SetUp();
        sessions_ = fs::temp_directory_path() / ("tripath-mpi-" + std::to_string(getpid()));
        fs::create_directories(sessions_);
    }
    void TearDown() override {
        fs::remove_all(sessions_);
        ShellTest::TearDown();
    }
    // The mpirun command line with this test's session folder.
    std::string mpirun() const { return "OMPI_MCA_orte_tmpdir_base='" + sessions_.string() + "' " + kMpirun; }
    // `tripath <args>` alone (ranks == 0) or under mpirun with that many ranks.
    Outcome tripath(const std::string& args, int ranks = 0) const {
        return shell((ranks > 0 ? mpirun() + " -np " + std::to_string(ranks) + " " : std::string()) + kTripath + " " + args);
    }

private:
    fs::path sessions_;
};

struct Rendered {
    Image image;
    Metadata meta;
};

Rendered load(const std::string& file) {
    Rendered r;
    r.image = readExr(file, &r.meta);
    return r;
}

// Bit for bit in every pixel, and equal in every metadata key but the time taken, the memory
// estimate (a resumed or checkpointed render holds more films) and the number of ranks
// (tripath:ranks), which must say `ranks`.
void expectSameRender(const Rendered& a, const Rendered& b, int ranks, const std::string& what) {
    ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size()) << what;
    size_t differing = 0;
    for (size_t i = 0; i < a.image.rgb.size(); ++i)
        differing += std::memcmp(&a.image.rgb[i], &b.image.rgb[i], sizeof(float)) != 0;
    EXPECT_EQ(differing, 0u) << what << ": values differing in their bits";
    auto strip = [](Metadata m, int* r) {
        std::erase_if(m, [&](const auto& kv) {
            if (kv.first == "tripath:ranks") *r = std::stoi(kv.second);
            return kv.first == "tripath:seconds" || kv.first == "tripath:memory-estimate" || kv.first == "tripath:ranks";
        });
        return m;
    };
    int ranksA = -1, ranksB = -1;
    EXPECT_EQ(strip(a.meta, &ranksA), strip(b.meta, &ranksB)) << what;
    EXPECT_EQ(ranksA, 1) << what;
    EXPECT_EQ(ranksB, ranks) << what;
}

// Ranks 1, 2 and 3 against one process with two threads, every integrator, on a built-in. 10
// passes are blocks of 4, 4 and 2: with three ranks, each renders one block, one of them short;
// mlt's ranks each run every third chain through every pass; auto's choose together after 4 and
// 8 passes, the ranks without a block of the stretch waiting (its plans are in the metadata).
TEST_F(Distributed, EveryRankCountGivesTheImageOfOneProcess) {
    for (const std::string integrator : {"pt", "lt", "bdpt", "vcm", "bpm", "ppm", "mlt", "auto"}) {
        const std::string args = "render --scene cornell-spheres --integrator " + integrator +
                                 " --width 24 --height 20 --spp 10 --seed 3 --out ";
        ASSERT_EQ(tripath(args + path("one.exr") + " --threads 2").exitCode, 0) << integrator;
        const Rendered one = load(path("one.exr"));
        for (int ranks = 1; ranks <= 3; ++ranks) {
            const std::string out = path("n" + std::to_string(ranks) + ".exr");
            const Outcome o = tripath(args + out + " --threads 1", ranks);
            ASSERT_EQ(o.exitCode, 0) << integrator << " on " << ranks << " ranks: " << o.err;
            expectSameRender(one, load(out), ranks, integrator + " on " + std::to_string(ranks) + " ranks");
        }
    }
}

// The film's exact totals (film.h), word for word: the EXR's floats would hide a sum reduced in
// double in another order (its rounding error is 2^-29 of a float's), so this compares the totals
// that a reference's checkpoint keeps.
TEST_F(Distributed, TheFilmsExactTotalsAgreeWordForWord) {
    auto totals = [](const std::string& file) {
        std::ifstream in(file, std::ios::binary);
        std::string line, passes;
        while (std::getline(in, line) && !line.empty())
            if (line.rfind("passes=", 0) == 0) passes = line;
        std::stringstream words;
        words << in.rdbuf();
        return passes + "|" + words.str();
    };
    for (const std::string integrator : {"lt", "bdpt"}) {
        std::string one;
        for (int ranks = 0; ranks <= 3; ++ranks) {
            const std::string out = path(integrator + std::to_string(ranks) + ".exr");
            const std::string args = "reference --scene cornell-spheres --integrator " + integrator +
                                     " --width 24 --height 20 --spp 10 --threads 1 --checkpoint 1000 --out " + out;
            const Outcome o = tripath(args, ranks);
            ASSERT_EQ(o.exitCode, 0) << o.err;
            const std::string mine = totals(out + ".checkpoint");
            ASSERT_GT(mine.size(), 24u * 20 * 3 * 24) << integrator;
            if (ranks == 0) one = mine;
            EXPECT_TRUE(mine == one) << integrator << " on " << ranks << " ranks";
        }
    }
}

// The same on a glTF scene under a sky given on the command line, with depth images (every film
// layer goes through the reduction).
TEST_F(Distributed, AGltfSceneUnderASkyAndItsDepthImagesToo) {
    ASSERT_EQ(tripath("export --scene cornell --out " + path("box.gltf")).exitCode, 0);
    for (const std::string integrator : {"pt", "lt", "bdpt"}) {
        const std::string args = "render --scene " + path("box.gltf") + " --integrator " + integrator +
                                 " --environment 0.3,0.4,0.5 --width 20 --height 20 --spp 9 --max-depth 4 --depth-images --threads 1 --out ";
        ASSERT_EQ(tripath(args + path("one.exr")).exitCode, 0) << integrator;
        ASSERT_EQ(tripath(args + path("two.exr"), 2).exitCode, 0) << integrator;
        expectSameRender(load(path("one.exr")), load(path("two.exr")), 2, integrator);
        for (int k = 1; k <= 4; ++k) {
            const std::string layer = "-k" + std::to_string(k) + ".exr";
            expectSameRender(load(path("one" + layer)), load(path("two" + layer)), 2, integrator + " k=" + std::to_string(k));
        }
    }
}

// The built-in sky, lit by its environment alone and reading its ground's texture, on 1 and 2
// ranks against one process.
TEST_F(Distributed, ASkyAndATextureToo) {
    for (const std::string integrator : {"bdpt", "vcm"}) {
        const std::string args = "render --scene sky --integrator " + integrator + " --width 24 --height 16 --spp 4 --out ";
        ASSERT_EQ(tripath(args + path("one.exr") + " --threads 2").exitCode, 0) << integrator;
        const Outcome o = tripath(args + path("two.exr") + " --threads 1", 2);
        ASSERT_EQ(o.exitCode, 0) << integrator << ": " << o.err;
        expectSameRender(load(path("one.exr")), load(path("two.exr")), 2, integrator + " on the sky");
    }
}

// Starts `cmd` in the background and, as soon as `file` exists, sends `signal` (SIGKILL by
// default) to the newest process matching `victimPattern`. Returns the command's exit status.
int killWhenWritten(const std::string& cmd, const std::string& file, const std::string& victimPattern, const fs::path& dir,
                    const std::string& signal = "KILL") {
    const std::string pidFile = (dir / "pid").string();
    std::system(("(" + cmd + " > /dev/null 2>&1; echo $? > '" + (dir / "status").string() + "') & echo $! > '" + pidFile + "'").c_str());
    const auto start = std::chrono::steady_clock::now();
    while (!fs::exists(file) && std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    // The newest process whose command line matches: the render itself, or the last rank mpirun
    // started. (The pattern is anchored at the binary's path, so that no shell matches it.)
    std::system(("pkill -" + signal + " -n -f '" + victimPattern + "'").c_str());
    const auto waitStart = std::chrono::steady_clock::now();
    while (!fs::exists(dir / "status") && std::chrono::steady_clock::now() - waitStart < std::chrono::seconds(120))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the status line written in full
    std::ifstream in(dir / "status");
    int status = -1;
    in >> status;
    return status;
}

// A --spp render killed (SIGKILL) after its first checkpoint and started again, on two ranks
// this time, ends bit-identical to an uninterrupted one-process render, and leaves no checkpoint:
// for mlt, every chain goes on from the state the checkpoint kept; auto chooses the same plans
// from the moments, the pixel weights and the schedule the checkpoint kept (on the caustic, it
// fails with the moments or the weights not restored, checked).
TEST_F(Distributed, AResumedCheckpointedRenderEqualsAnUninterruptedOne) {
    for (const std::string integrator : {"bdpt", "mlt", "auto"}) {
        // auto on the caustic, where its choices depend on every piece of the state it keeps.
        const std::string scene = integrator == "auto" ? "caustic" : "cornell";
        const std::string args = "render --scene " + scene + " --integrator " + integrator +
                                 " --width 64 --height 64 --spp 120 --threads 1 --out ";
        ASSERT_EQ(tripath(args + path("whole.exr")).exitCode, 0);
        const std::string out = path(integrator + "-cut.exr"), checkpoint = out + ".checkpoint";
        const std::string cmd = kTripath + " " + args + out + " --checkpoint 0.05";
        const int status = killWhenWritten(cmd, checkpoint, "^" + std::string(TRIPATH_BINARY) + ".* --out " + out, dir_);
        ASSERT_NE(status, 0) << integrator << ": the render finished before it was killed: make it longer";
        ASSERT_TRUE(fs::exists(checkpoint));
        const Outcome o = tripath(args + out + " --checkpoint 0.05", 2);
        ASSERT_EQ(o.exitCode, 0) << o.err;
        EXPECT_NE(o.err.find("continuing from"), std::string::npos) << o.err;
        expectSameRender(load(path("whole.exr")), load(out), 2, integrator + " resumed");
        EXPECT_FALSE(fs::exists(checkpoint)) << "a finished render keeps no checkpoint";
    }
}

// A reference run twice with a checkpoint (8 spp, then 8 more on two ranks) is the 16-spp
// reference rendered at once, bit for bit: the second run goes on from the first's exact totals
// (mlt's from its chains' states, auto's from its moments and plans).
TEST_F(Distributed, AReferenceAddsToItsCheckpointExactly) {
    for (const std::string integrator : {"bdpt", "mlt", "auto"}) {
        const std::string args = "reference --scene cornell-spheres --integrator " + integrator +
                                 " --width 24 --height 20 --threads 1 ";
        const std::string once = path(integrator + "-once.exr"), twice = path(integrator + "-twice.exr");
        ASSERT_EQ(tripath(args + "--spp 16 --out " + once).exitCode, 0);
        ASSERT_EQ(tripath(args + "--spp 8 --checkpoint 1000 --out " + twice).exitCode, 0);
        const Outcome o = tripath(args + "--spp 8 --out " + twice, 2);
        ASSERT_EQ(o.exitCode, 0) << o.err;
        expectSameRender(load(once), load(twice), 2, integrator + " continued reference");
    }
}

// Ctrl-C to mpirun (which passes SIGTERM to its ranks): every rank stops at its next pass, and the
// image so far is written, with whole passes.
TEST_F(Distributed, InterruptingMpirunWritesTheImageSoFar) {
    const std::string out = path("int.exr");
    const std::string cmd = mpirun() + " -np 2 " + kTripath + " render --scene cornell --width 32 --height 32 --threads 1 "
                            "--spp 100000 --checkpoint 0.05 --out " + out;
    killWhenWritten(cmd, out + ".checkpoint", "^" + std::string(TRIPATH_MPIEXEC) + ".* --out " + out, dir_, "INT");
    ASSERT_TRUE(fs::exists(out));
    const Rendered r = load(out);
    const auto spp = std::find_if(r.meta.begin(), r.meta.end(), [](const auto& kv) { return kv.first == "tripath:spp"; });
    ASSERT_NE(spp, r.meta.end());
    EXPECT_GT(std::stoi(spp->second), 0);
    EXPECT_LT(std::stoi(spp->second), 100000);
    for (float v : r.image.rgb) ASSERT_TRUE(std::isfinite(v));
}

// A rank killed mid-render ends the whole job with a non-zero exit; the last checkpoint is whole
// and a render continues from it.
TEST_F(Distributed, AKilledRankEndsTheJobAndTheLastCheckpointStaysLoadable) {
    const std::string out = path("job.exr"), checkpoint = out + ".checkpoint";
    const std::string args = "render --scene cornell --integrator pt --width 64 --height 64 --threads 1 --checkpoint 0.05 --out " + out;
    const int status = killWhenWritten(mpirun() + " -np 2 " + kTripath + " " + args + " --spp 100000", checkpoint,
                                       "^" + std::string(TRIPATH_BINARY) + ".* --out " + out, dir_);
    EXPECT_NE(status, 0);
    EXPECT_NE(status, 124) << "the job hung until `timeout` ended it";
    ASSERT_TRUE(fs::exists(checkpoint));
    std::ifstream in(checkpoint);
    int passes = 0;
    for (std::string line; std::getline(in, line) && !line.empty();)
        if (line.rfind("passes=", 0) == 0) passes = std::stoi(line.substr(7));
    ASSERT_GT(passes, 0);
    const Outcome o = tripath(args + " --spp " + std::to_string(passes + 4));
    ASSERT_EQ(o.exitCode, 0) << o.err;
    const Rendered r = load(out);
    EXPECT_NE(std::find(r.meta.begin(), r.meta.end(), std::make_pair(std::string("tripath:spp"), std::to_string(passes + 4))),
              r.meta.end());
}

// A rank that cannot read the scene (here: rank 1 starts in a folder without it, as a node without
// the file would) ends the job: one error line from rank 0 naming rank 1 and the reason, a
// non-zero exit, no image, no hang.
TEST_F(Distributed, ARankThatCannotReadTheSceneEndsTheJobWithItsReason) {
    fs::create_directories(dir_ / "has");
    fs::create_directories(dir_ / "lacks");
    ASSERT_EQ(tripath("export --scene cornell --out " + path("has/scene.gltf")).exitCode, 0);
    const std::string render = kTripath + " render --scene scene.gltf --spp 2 --width 16 --height 16 --out " + path("out.exr");
    const Outcome o = shell(mpirun() + " -np 1 --wdir '" + path("has") + "' " + render + " : -np 1 --wdir '" +
                            path("lacks") + "' " + render);
    EXPECT_NE(o.exitCode, 0);
    EXPECT_NE(o.exitCode, 124) << "the job hung until `timeout` ended it";
    EXPECT_FALSE(fs::exists(path("out.exr")));
    std::istringstream lines(o.err);
    int ours = 0;
    for (std::string l; std::getline(lines, l);)
        if (l.rfind("error: ", 0) == 0) {
            ++ours;
            EXPECT_NE(l.find("rank 1"), std::string::npos) << l;
            EXPECT_NE(l.find("scene.gltf"), std::string::npos) << l;
        }
    EXPECT_EQ(ours, 1) << o.err;
}

// compare on two ranks: the reference rendered by both together, the four runs dealt out and
// gathered into one report on rank 0 with every run of every method.
TEST_F(Distributed, CompareGathersEveryRunFromEveryRank) {
    const Outcome o = tripath("compare --scene cornell --integrators pt,lt --runs 2 --time 0.2 --width 16 --height 16 "
                              "--threads 1 --out " + path("cmp"), 2);
    ASSERT_EQ(o.exitCode, 0) << o.err;
    std::ifstream in(path("cmp/counters.csv"));
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(line.substr(0, line.find(',', line.find(',') + 1)));
    EXPECT_EQ(rows, (std::vector<std::string>{"integrator,run", "pt,0", "lt,0", "pt,1", "lt,1"}));
    for (const char* file : {"pt.exr", "lt.exr", "reference.exr", "index.html"}) EXPECT_TRUE(fs::exists(path(std::string("cmp/") + file))) << file;
    const Rendered ref = load(path("cmp/reference.exr"));
    EXPECT_NE(std::find(ref.meta.begin(), ref.meta.end(), std::make_pair(std::string("tripath:ranks"), std::string("2"))),
              ref.meta.end());
}

// Bad input under mpirun: every rank finds it, rank 0 alone says it, the job exits non-zero.
TEST_F(Distributed, BadInputGivesOneErrorLineFromRankZero) {
    const Outcome o = tripath("render --scene cornell --spp 0 --out " + path("out.exr"), 2);
    EXPECT_NE(o.exitCode, 0);
    EXPECT_NE(o.exitCode, 124) << "the job hung until `timeout` ended it";
    EXPECT_EQ(o.err.rfind("error: --spp", 0), 0u) << o.err;
    EXPECT_EQ(o.err.find("error:", 1), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(path("out.exr")));
}

}  // namespace
}  // namespace tripath
