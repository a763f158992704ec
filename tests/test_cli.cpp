// The command line under bad input (docs/design.md §5): every mistake ends with a non-zero exit code and
// one line on stderr saying what is wrong, before any rendering starts, and no output file.
// Each test runs the real binary (TRIPATH_BINARY) through the shell.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "integrators/integrator.h"
#include "scenes/builtin_scenes.h"
#include "io/gltf_writer.h"
#include "image/image.h"
#include "textured_scenes.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

struct Outcome {
    int exitCode = -1;
    std::string out, err;
    std::vector<std::string> errLines() const {
        std::vector<std::string> lines;
        std::istringstream in(err);
        for (std::string l; std::getline(in, l);)
            if (!l.empty()) lines.push_back(l);
        return lines;
    }
};

// Whether `done` came true within `seconds`, asking every 20 ms.
bool waitFor(const std::function<bool()>& done, int seconds) {
    const auto start = std::chrono::steady_clock::now();
    while (!done() && std::chrono::steady_clock::now() - start < std::chrono::seconds(seconds))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return done();
}

// `tripath <args>` running on its own, stdout discarded and stderr into `errFile`, to be sent a
// real signal as a batch system or a terminal would. Killed if the test ends before it does.
class Background {
public:
    Background(const std::vector<std::string>& args, const std::string& errFile) {
        std::vector<std::string> all{TRIPATH_BINARY};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (std::string& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t files;
        posix_spawn_file_actions_init(&files);
        posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&files, 2, errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (posix_spawn(&pid_, TRIPATH_BINARY, &files, nullptr, argv.data(), environ) != 0) pid_ = -1;
        posix_spawn_file_actions_destroy(&files);
    }
    ~Background() {
        if (pid_ <= 0) return;
        ::kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
    }
    void signal(int number) const { ::kill(pid_, number); }
    // Whether it has installed a handler for signal `number` (the SigCgt mask of /proc/PID/status):
    // from then on that signal reaches the program instead of ending it.
    bool catches(int number) const {
        std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
        for (std::string line; std::getline(status, line);)
            if (line.starts_with("SigCgt:")) return (std::stoull(line.substr(7), nullptr, 16) >> (number - 1)) & 1;
        return false;
    }
    // Its exit code once it ends within `seconds`; -1 if a signal ended it or it did not end.
    int exitCode(int seconds) {
        int status = 0;
        bool ended = false;
        if (!waitFor([&] { return ended = ended || waitpid(pid_, &status, WNOHANG) == pid_; }, seconds)) return -1;
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }

private:
    pid_t pid_ = -1;
};

std::string metaValue(const Metadata& meta, const std::string& key) {
    for (const auto& [k, v] : meta)
        if (k == key) return v;
    return "";
}

// A fresh folder per test, removed afterwards.
class Cli : public testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("tripath-cli-" + std::to_string(getpid()) + "-" +
                testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // `tripath render` of cornell for a million passes, checkpointing every 10 ms into
    // out.exr.checkpoint, its stderr in err.txt: returned once its first checkpoint is written
    // (its signal handler long installed by then), to be sent signals.
    std::unique_ptr<Background> longRenderUnderWay() const {
        auto job = std::make_unique<Background>(
            std::vector<std::string>{"render", "--scene", "cornell", "--width", "32", "--height", "32", "--spp",
                                     "1000000", "--checkpoint", "0.01", "--out", path("out.exr")},
            path("err.txt"));
        EXPECT_TRUE(waitFor([&] { return fs::exists(path("out.exr.checkpoint")); }, 120)) << slurp(path("err.txt"));
        return job;
    }

    // Runs `tripath <args>`. `timeout` only keeps a broken build from hanging the suite: a
    // command that starts rendering when it should refuse would run for hours and end with
    // exit code 124, which the tests reject along with every other wrong code.
    Outcome run(const std::string& args, int timeoutSeconds = 300) const {
        const std::string out = path("stdout.txt"), err = path("stderr.txt");
        const std::string cmd = "timeout " + std::to_string(timeoutSeconds) + " '" TRIPATH_BINARY "' " + args + " >'" +
                                out + "' 2>'" + err + "'";
        const int status = std::system(cmd.c_str());
        Outcome o;
        o.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        o.out = slurp(out);
        o.err = slurp(err);
        return o;
    }

    static std::string slurp(const std::string& file) {
        std::ifstream in(file);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    // The contract: exit code 1 (an input error, not a crash or a timeout), exactly one line on
    // stderr that starts with "error: " and mentions `expected`, and no output image.
    void expectRefused(const std::string& args, const std::string& expected, int timeoutSeconds = 300) const {
        const Outcome o = run(args, timeoutSeconds);
        EXPECT_EQ(o.exitCode, 1) << args << "\n" << o.err;
        const auto lines = o.errLines();
        ASSERT_EQ(lines.size(), 1u) << args << "\nstderr:\n" << o.err;
        EXPECT_EQ(lines[0].rfind("error: ", 0), 0u) << lines[0];
        EXPECT_NE(lines[0].find(expected), std::string::npos) << "expected '" << expected << "' in: " << lines[0];
        EXPECT_FALSE(fs::exists(path("out.exr"))) << args;
    }

    std::string render(const std::string& rest) const { return "render --scene cornell " + rest; }
    std::string out() const { return "--out '" + path("out.exr") + "'"; }

    fs::path dir_;
};

TEST_F(Cli, ARenderThatIsFineSucceeds) {
    // The reference point for the rest: the same command lines with one thing wrong fail.
    const Outcome o = run(render("--width 8 --height 8 --spp 1 " + out()));
    EXPECT_EQ(o.exitCode, 0) << o.err;
    EXPECT_EQ(o.err.find("interrupted"), std::string::npos) << o.err;
    Metadata meta;
    readExr(path("out.exr"), &meta);
    EXPECT_EQ(metaValue(meta, "tripath:interrupted"), "") << "a render that ran to its end";
}

// SIGTERM (a batch system's time limit) or SIGINT (Ctrl-C) mid-render: the image so far is
// written, but the command must not pass for finished: it exits with 128 + the signal's number, as
// a shell reports a process the signal ended, its summary line says how far it got, and the EXR
// records tripath:interrupted. The render checkpoints every 10 ms only to show it is under way
// (the file appears after its first passes, its signal handler long installed). Catches an
// interrupted render that exits 0 and says nothing, and a line or key whose pass
// count is not the file's.
TEST_F(Cli, AnInterruptedRenderSaysSoAndFails) {
    const auto job = longRenderUnderWay();
    job->signal(SIGTERM);
    EXPECT_EQ(job->exitCode(120), 128 + SIGTERM) << slurp(path("err.txt"));
    Metadata meta;
    readExr(path("out.exr"), &meta);
    const std::string spp = metaValue(meta, "tripath:spp"), progress = "after " + spp + " of 1000000 passes, ";
    EXPECT_EQ(metaValue(meta, "tripath:interrupted").rfind(progress, 0), 0u) << metaValue(meta, "tripath:interrupted");
    EXPECT_NE(slurp(path("err.txt")).find("bdpt cornell: interrupted " + progress), std::string::npos)
        << slurp(path("err.txt"));
}

// A second signal, while the render winds down after the first, ends the process at once, as a
// user pressing Ctrl-C twice means, and says so rather than vanishing without a word; the exit
// code is the first signal's. The two are sent together: the render cannot finish in between.
TEST_F(Cli, ASecondSignalExitsAtOnceAndSaysSo) {
    const auto job = longRenderUnderWay();
    job->signal(SIGTERM);
    job->signal(SIGINT);
    const int code = job->exitCode(120);
    EXPECT_TRUE(code == 128 + SIGTERM || code == 128 + SIGINT) << code;
    const std::string err = slurp(path("err.txt"));
    EXPECT_NE(err.find("interrupted again: exiting at once, without writing what the render has\n"), std::string::npos)
        << err;
}

// A checkpoint that cannot be written (here its temporary's name is too long for the file system,
// where the image's is not; a full disk in practice) is warned about once, and the render goes on
// to its end and writes its image, rather than stopping with the error.
TEST_F(Cli, AFailedCheckpointWriteWarnsOnceAndTheRenderGoesOn) {
    // 234 bytes: "<name>.tmp-<pid>-<n>.exr" stays within 255, "<name>.checkpoint.tmp-<pid>-<n>.part" does not.
    const std::string image = path(std::string(230, 'x') + ".exr");
    const Outcome o =
        run(render("--width 16 --height 16 --spp 64 --threads 1 --checkpoint 0.000001 --out '" + image + "'"));
    EXPECT_EQ(o.exitCode, 0) << o.err;
    EXPECT_TRUE(fs::exists(image));
    size_t warnings = 0;
    for (const std::string& line : o.errLines())
        warnings += line.starts_with("warning: cannot write '" + image + ".checkpoint'") &&
                    line.ends_with("; rendering on without this checkpoint");
    EXPECT_EQ(warnings, 1u) << o.err;
}

// The same for `reference` with a time budget, which keeps the passes it has: the line and the key
// say the passes and the seconds out of the budget.
TEST_F(Cli, AnInterruptedReferenceSaysSoAndFails) {
    Background job({"reference", "--scene", "cornell", "--width", "32", "--height", "32", "--time", "1000",
                    "--checkpoint", "0.01", "--out", path("ref.exr")},
                   path("err.txt"));
    ASSERT_TRUE(waitFor([&] { return fs::exists(path("ref.exr.checkpoint")); }, 120)) << slurp(path("err.txt"));
    job.signal(SIGINT);
    EXPECT_EQ(job.exitCode(120), 128 + SIGINT) << slurp(path("err.txt"));
    Metadata meta;
    readExr(path("ref.exr"), &meta);
    const std::string spp = metaValue(meta, "tripath:spp"), progress = "after " + spp + " passes, ";
    EXPECT_GE(std::stoi(spp), 1);
    const std::string recorded = metaValue(meta, "tripath:interrupted");
    EXPECT_EQ(recorded.rfind(progress, 0), 0u) << recorded;
    EXPECT_NE(recorded.find(" s of 1000 s"), std::string::npos) << recorded;
    EXPECT_NE(slurp(path("err.txt")).find("reference bdpt cornell: interrupted " + progress), std::string::npos)
        << slurp(path("err.txt"));
}

// Ctrl-C during mlt's bootstrap (here the largest, 10^7 samples: 20 s on two busy cores) stops it
// at once. It has no pass, so it writes no image (an all-black EXR would pass for a render) and no
// checkpoint (the chains of a partial bootstrap are not those a resumed run redoes): one line says
// so, and the exit code is the interrupted one. The signal is sent once the handler is installed,
// just before the bootstrap starts. Catches a bootstrap that runs to its end before looking at the
// signal (it then renders a pass and writes both, or outlasts the 20 s wait), and an interrupted
// bootstrap that writes an image or a checkpoint.
TEST_F(Cli, MltInterruptedInItsBootstrapWritesNothingAndSaysSo) {
    Background job({"render", "--scene", "cornell", "--integrator", "mlt", "--bootstrap", "10000000", "--width", "8",
                    "--height", "8", "--spp", "4", "--checkpoint", "0.01", "--out", path("out.exr")},
                   path("err.txt"));
    ASSERT_TRUE(waitFor([&] { return job.catches(SIGINT); }, 120)) << slurp(path("err.txt"));
    job.signal(SIGINT);
    EXPECT_EQ(job.exitCode(20), 128 + SIGINT) << slurp(path("err.txt"));
    EXPECT_EQ(slurp(path("err.txt")), "mlt cornell: interrupted in mlt's bootstrap, before its first pass: no image\n");
    EXPECT_FALSE(fs::exists(path("out.exr")));
    EXPECT_FALSE(fs::exists(path("out.exr.checkpoint")));
}

TEST_F(Cli, StatsReportWhatTheRenderDidAndWhereTheTimeWent) {
    const Outcome o = run(render("--width 32 --height 32 --spp 2 --integrator bdpt --stats " + out()));
    EXPECT_EQ(o.exitCode, 0) << o.err;
    for (const char* line : {"closest-hit rays", "shadow rays", "BSDF evaluations", "connections", "splats",
                             "rays of both kinds"})
        EXPECT_NE(o.err.find(line), std::string::npos) << line << " missing from:\n" << o.err;
    const Outcome plain = run(render("--width 32 --height 32 --spp 2 " + out()));
    EXPECT_EQ(plain.err.find("closest-hit rays"), std::string::npos) << "without --stats, no report:\n" << plain.err;
}

// auto's EXR holds its classes per pixel beside the image (channels auto.pt, auto.connect,
// auto.trace, auto.merge): 1 where the pixel's 16×16 tile ran the class in the last stretch, as
// tripath:auto-tiles names them (a row of tiles per "; "). At 40×24 the last column and row of
// tiles are cut short. Fails if the render command leaves the channels out or writes them for a
// tile other than the pixel's; another method's EXR has none.
TEST_F(Cli, AutosExrSaysPerPixelWhichClassesItsTileRan) {
    const Outcome o = run(render("--integrator auto --width 40 --height 24 --spp 20 " + out()));
    ASSERT_EQ(o.exitCode, 0) << o.err;
    Metadata meta;
    std::vector<ExrChannel> channels;
    readExr(path("out.exr"), &meta, &channels);
    std::vector<std::vector<std::string>> tiles;  // the classes' names of each tile, row by row
    std::istringstream rows(metaValue(meta, "tripath:auto-tiles"));
    for (std::string row; std::getline(rows, row, ';');) {
        std::istringstream names(row);
        tiles.emplace_back(std::istream_iterator<std::string>(names), std::istream_iterator<std::string>());
    }
    ASSERT_EQ(tiles.size(), 2u) << metaValue(meta, "tripath:auto-tiles");
    ASSERT_EQ(channels.size(), 4u);
    for (const ExrChannel& c : channels) {
        const std::string name = c.name.substr(c.name.find('.') + 1);
        ASSERT_EQ(c.values.size(), 40u * 24u) << c.name;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 40; ++x) {
                ASSERT_EQ(tiles[size_t(y / 16)].size(), 3u);
                const std::string& tile = tiles[size_t(y / 16)][size_t(x / 16)];
                const bool runs = ("+" + tile + "+").find("+" + name + "+") != std::string::npos;
                ASSERT_EQ(c.values[size_t(y * 40 + x)], runs ? 1.0f : 0.0f) << c.name << " at " << x << "," << y << ": " << tile;
            }
    }
    ASSERT_EQ(run(render("--integrator bdpt --width 40 --height 24 --spp 1 " + out())).exitCode, 0);
    readExr(path("out.exr"), &meta, &channels);
    EXPECT_TRUE(channels.empty());
}

// A comparison is held to its budget as a whole, before its first render: pt at 512² fits 250 MiB
// (173 MiB), but not with the images the comparison keeps and the report it draws. Fails if the
// comparison's own check is missing: each render would pass its own and the report be written.
TEST_F(Cli, ACompareOverItsMemoryLimitIsRefusedBeforeItsFirstRender) {
    const Outcome reference = run(render("--width 512 --height 512 --spp 1 --seed 99 --integrator pt " + out()));
    ASSERT_EQ(reference.exitCode, 0) << reference.err;
    const std::string compare = "compare --scene cornell --integrators pt --width 512 --height 512 --time 1 --reference '" +
                                path("out.exr") + "' --out '" + path("c") + "' ";
    const Outcome o = run(compare + "--memory-limit 250M");
    EXPECT_EQ(o.exitCode, 1) << o.err;
    ASSERT_EQ(o.errLines().size(), 1u) << o.err;
    EXPECT_NE(o.err.find("needs an estimated"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("report"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(path("c")));
    EXPECT_EQ(run(compare + "--memory-limit 1G").exitCode, 0);
}

// --integrator's help explains every method the flag accepts. Fails if one is left out, as auto
// was when it came.
TEST_F(Cli, TheIntegratorsHelpNamesEveryMethod) {
    const Outcome help = run("render --help");
    const size_t start = help.out.find("--integrator");
    ASSERT_NE(start, std::string::npos) << help.out;
    const std::string text = help.out.substr(start, help.out.find("\n  --", start) - start);
    for (const std::string& name : kIntegratorNames)
        EXPECT_NE(text.find(" " + name + ": "), std::string::npos) << name << " missing from: " << text;
}

// --help's limits are the limits: each side from 1 to 16384 renders, 0 and 16385 are refused. Fails
// if the help and the check disagree at either end, as they did when 16384² was refused as a size.
TEST_F(Cli, TheImageSidesHelpsLimitsAreTheLimits) {
    const Outcome help = run("render --help");
    for (const char* flag : {"--width INT:INT in [1, 16384]", "--height INT:INT in [1, 16384]"})
        EXPECT_NE(help.out.find(flag), std::string::npos) << flag << " missing from:\n" << help.out;
    for (const char* sides : {"--width 16384 --height 1", "--width 1 --height 16384", "--width 1 --height 1"}) {
        const Outcome o = run(render(std::string(sides) + " --spp 1 --integrator pt " + out()));
        EXPECT_EQ(o.exitCode, 0) << sides << "\n" << o.err;
        fs::remove(path("out.exr"));
    }
    expectRefused(render("--width 16385 " + out()), "--width must be between 1 and 16384 (got 16385)");
    expectRefused(render("--height 16385 " + out()), "--height must be between 1 and 16384 (got 16385)");
    expectRefused(render("--width 0 " + out()), "--width must be between 1 and 16384 (got 0)");
    expectRefused(render("--height 0 " + out()), "--height must be between 1 and 16384 (got 0)");
    // 16384² is a size like any other: whether it fits is the memory estimate's to say.
    expectRefused(render("--integrator pt --width 16384 --height 16384 --memory-limit 1G " + out()),
                  "the render needs an estimated");
}

// A render whose estimate exceeds --memory-limit is refused in one line naming the estimate, the
// limit and what to lower, before any pass (a million passes would time the test out); with the
// limit raised it renders. Fails if the check is missing or comes after the rendering.
TEST_F(Cli, ARenderOverItsMemoryLimitIsRefusedBeforeRendering) {
    expectRefused(render("--memory-limit 8X " + out()), "--memory-limit must be a size above 0 such as 8G, 512M or 1.5T (got '8X')");
    expectRefused(render("--memory-limit 0 " + out()), "--memory-limit must be a size above 0");
    expectRefused(render("--integrator vcm --width 64 --height 64 --spp 1000000 --memory-limit 100M " + out()),
                  "needs an estimated");
    const std::string line = run(render("--integrator vcm --width 64 --height 64 --spp 1000000 --memory-limit 100M " +
                                        out())).errLines().at(0);
    for (const char* part : {"(process 140 MiB, ", "but --memory-limit is 100 MiB: the process and its scene alone take 140 MiB"})
        EXPECT_NE(line.find(part), std::string::npos) << part << " missing from: " << line;
    const Outcome o = run(render("--integrator vcm --width 64 --height 64 --spp 1 --memory-limit 64G " + out()));
    EXPECT_EQ(o.exitCode, 0) << o.err;
    Metadata meta;
    readExr(path("out.exr"), &meta);
    EXPECT_GT(std::stoull(metaValue(meta, "tripath:memory-estimate")), uint64_t(140) << 20);
}

// A PNG file whose header (signature, IHDR with its CRC, IEND) claims width × height 8-bit RGB
// texels and that holds none (an empty IDAT): a decoder that allocated before looking would ask
// for 30 GB.
std::string pngHeaderClaiming(uint32_t width, uint32_t height) {
    auto crc32 = [](const std::string& bytes) {
        uint32_t crc = 0xffffffffu;
        for (unsigned char b : bytes) {
            crc ^= b;
            for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
        }
        return ~crc;
    };
    auto be32 = [](uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    auto chunk = [&](const std::string& type, const std::string& data) {
        return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
    };
    const std::string ihdr = be32(width) + be32(height) + std::string{8, 2, 0, 0, 0};
    const std::string emptyDeflate("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);
    return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", emptyDeflate) + chunk("IEND", "");
}

// A scene whose quad's base colour is the texture in file `uri` (next to it).
std::string sceneWithTexture(const fs::path& file, const std::string& uri) {
    test::TexturedScene s;
    s.addQuad({.material = s.addMaterial({{"emissiveFactor", {1, 1, 1}},
                                          {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", s.addTexture(uri)}}}}}})});
    return s.write(file);
}

TEST_F(Cli, OversizedAndUnreadableTexturesAreRefused) {
    std::ofstream(path("huge.png"), std::ios::binary) << pngHeaderClaiming(100000, 100000);
    expectRefused("render --scene '" + sceneWithTexture(path("huge.gltf"), "huge.png") + "' --spp 1 " + out(),
                  "its image claims 100000 x 100000 texels");
    std::ofstream(path("broken.png"), std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << "not a PNG after all";
    expectRefused("render --scene '" + sceneWithTexture(path("broken.gltf"), "broken.png") + "' --spp 1 " + out(),
                  "texture 0: cannot read its image");
}

TEST_F(Cli, ZeroAndNegativeSizesAreRefused) {
    expectRefused(render("--width 0 " + out()), "--width");
    expectRefused(render("--height 0 " + out()), "--height");
    expectRefused(render("--width -5 " + out()), "--width");
    expectRefused(render("--height -1 " + out()), "--height");
}

TEST_F(Cli, AbsurdBudgetsAreRefused) {
    expectRefused(render("--spp 100000000 " + out()), "--spp");
    expectRefused(render("--spp 0 " + out()), "--spp");
    expectRefused(render("--time 0 " + out()), "--time");
    expectRefused(render("--time 1e300 " + out()), "--time");
    expectRefused(render("--time nan " + out()), "--time");
    expectRefused(render("--max-depth 0 " + out()), "--max-depth");
    expectRefused(render("--checkpoint -1 " + out()), "--checkpoint");
    expectRefused(render("--width 8 --height 8 --replay 3 " + out()), "--replay");
    expectRefused(render("--width 8 --height 8 --replay 3,64 " + out()), "--replay");
    expectRefused(render("--width 8 --height 8 --replay -1,2 " + out()), "--replay");
    expectRefused(render("--width 8 --height 8 --replay 1,2x " + out()), "--replay");
    expectRefused(render("--integrator mlt --width 8 --height 8 --replay 1,2 " + out()), "mlt has no pixel samples");
    expectRefused(render("--checkpoint nan " + out()), "--checkpoint");
}

// An empty --environment (an unset shell variable) is refused, not taken as no environment: a
// scene lit only by it would otherwise be refused as having no emitter, or render unlit.
TEST_F(Cli, AnEmptyEnvironmentIsRefused) {
    expectRefused(render("--width 8 --height 8 --spp 1 --environment '' " + out()),
                  "--environment is empty: give a map's path or a radiance R,G,B");
}

TEST_F(Cli, NegativeBudgetsAreRefused) {
    // Small images, so that a regression fails quickly instead of rendering for long.
    expectRefused(render("--width 8 --height 8 --spp -1 " + out()), "--spp");
    expectRefused(render("--width 8 --height 8 --time -1 " + out()), "--time");
    expectRefused(render("--width 8 --height 8 --spp -5 " + out()), "--spp");
    expectRefused(render("--width 8 --height 8 --time -0.5 " + out()), "--time");
}

TEST_F(Cli, BadMergeRadiusSettingsAreRefused) {
    const std::string vcm = "--integrator vcm --width 8 --height 8 --spp 1 ";
    expectRefused(render(vcm + "--radius 0 " + out()), "--radius");
    expectRefused(render(vcm + "--radius -1 " + out()), "--radius");
    expectRefused(render(vcm + "--radius nan " + out()), "--radius");
    expectRefused(render(vcm + "--radius-factor 0 " + out()), "--radius-factor");
    expectRefused(render(vcm + "--radius-factor 2 " + out()), "--radius-factor");
    expectRefused(render(vcm + "--alpha 0 " + out()), "--alpha");
    expectRefused(render(vcm + "--alpha 1.5 " + out()), "--alpha");
    expectRefused(render(vcm + "--radius-pixels 0 " + out()), "--radius-pixels");
    expectRefused(render(vcm + "--radius 0.01 --radius-factor 0.01 " + out()), "--radius");
    expectRefused(render(vcm + "--radius-factor 0.01 --radius-pixels 2 " + out()), "--radius");
}

TEST_F(Cli, BadLightPathCountsAreRefused) {
    const std::string vcm = "--integrator vcm --width 8 --height 8 --spp 1 ";
    expectRefused(render(vcm + "--light-paths 0 " + out()), "--light-paths");
    expectRefused(render(vcm + "--light-paths -3 " + out()), "--light-paths");
    expectRefused(render(vcm + "--light-paths 67108865 " + out()), "--light-paths");
    expectRefused(render(vcm + "--light-paths many " + out()), "--light-paths");
}

// A merging reference continues its radius schedule from the passes in the file, so adding
// samples with another schedule would mix two different estimates: refused, and the file kept.
TEST_F(Cli, AReferenceIsNotContinuedWithAnotherRadiusSchedule) {
    const std::string ref = "reference --scene cornell --integrator vcm --width 8 --height 8 --spp 1 --out '" +
                            path("ref.exr") + "' ";
    ASSERT_EQ(run(ref).exitCode, 0);
    EXPECT_EQ(run(ref).exitCode, 0) << "the same schedule adds samples";
    const Outcome o = run(ref + "--alpha 0.5");
    EXPECT_EQ(o.exitCode, 1);
    EXPECT_NE(o.err.find("alpha"), std::string::npos) << o.err;
    const Outcome r = run(ref + "--radius 0.5");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("radius"), std::string::npos) << r.err;
    // η = π r² N_L: another light path count is another estimate too.
    const Outcome n = run(ref + "--light-paths 30");
    EXPECT_EQ(n.exitCode, 1);
    EXPECT_NE(n.err.find("light-paths"), std::string::npos) << n.err;
    EXPECT_EQ(run(ref + "--light-paths 64").exitCode, 0) << "64 is the one per pixel of 8x8, as the file was made";
}

TEST_F(Cli, OutputInAMissingFolderIsRefusedBeforeRendering) {
    // A budget of hours: refusing must come before rendering, or this would time out.
    expectRefused(render("--spp 1000000 --width 4096 --height 4096 --out '" + path("missing/out.exr") + "'"),
                  "does not exist");
    expectRefused(render("--spp 1 --width 8 --height 8 " + out() + " --png '" + path("missing/out.png") + "'"),
                  "does not exist");
}

TEST_F(Cli, OutputInAReadOnlyFolderIsRefused) {
    // /proc refuses new files even to root, so this holds whoever runs the tests.
    expectRefused(render("--spp 1000000 --width 4096 --height 4096 --out /proc/tripath-out.exr"), "/proc");
}

TEST_F(Cli, OutputOfTheWrongTypeIsRefused) { expectRefused(render("--out '" + path("out.png") + "'"), ".exr"); }

TEST_F(Cli, MissingSceneFileIsRefused) {
    expectRefused("render --scene '" + path("nothing.gltf") + "' " + out(), "not found");
}

TEST_F(Cli, BrokenGltfIsRefused) {
    std::ofstream(path("broken.gltf")) << "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ {";
    expectRefused("render --scene '" + path("broken.gltf") + "' " + out(), "broken.gltf");
    std::ofstream(path("garbage.glb"), std::ios::binary) << "glTF\x02\x00\x00\x00garbage";
    expectRefused("render --scene '" + path("garbage.glb") + "' " + out(), "garbage.glb");
    std::ofstream(path("empty.gltf"));
    expectRefused("render --scene '" + path("empty.gltf") + "' " + out(), "empty.gltf");
}

TEST_F(Cli, UnknownBuiltinIsRefused) { expectRefused("render --scene no-such-scene " + out(), "no-such-scene"); }

TEST_F(Cli, UnknownIntegratorIsRefused) { expectRefused(render("--integrator pssmlt " + out()), "pssmlt"); }

TEST_F(Cli, SceneWithoutEmitterIsRefused) {
    SceneDesc dark = builtinScene("contact");
    for (Material& m : dark.materials) m.emission = Spectrum(0.0f);
    writeGltf(dark, path("dark.gltf"), [](const std::string&) {});
    expectRefused("render --scene '" + path("dark.gltf") + "' " + out(), "no emitter");
}

TEST_F(Cli, ValidationComesBeforeLoading) {
    // Both the size and the scene are wrong: the cheap check speaks first.
    expectRefused("render --scene '" + path("nothing.gltf") + "' --width 0 " + out(), "--width");
}

// A number too large for its flag's type is out of range like any other, and gets the range, not
// CLI11's "could not convert". Catches a flag whose text reaches CLI11's conversion unchecked.
TEST_F(Cli, IntegersBeyondTheirTypeGiveTheRange) {
    const std::string tiny = "--width 8 --height 8 --spp 1 ";
    expectRefused(render("--spp 99999999999 " + out()), "--spp must be between 1 and 1000000 (got 99999999999)");
    expectRefused(render("--width 99999999999 " + out()), "--width must be between 1 and 16384");
    expectRefused(render("--height 99999999999 " + out()), "--height must be between 1 and 16384");
    expectRefused(render(tiny + "--max-depth 99999999999 " + out()), "--max-depth must be between 1 and 1024");
    expectRefused(render(tiny + "--rr-depth 99999999999 " + out()), "--rr-depth must be between 0 and 1024");
    expectRefused(render(tiny + "--threads 99999999999 " + out()), "--threads must be between 0 and 4096");
    expectRefused(render(tiny + "--integrator vcm --light-paths 99999999999999999999 " + out()),
                  "--light-paths must be between 1 and 268435456");
    expectRefused(render(tiny + "--strategy-images 99999999999 " + out()), "--strategy-images must be between 0 and 16");
    expectRefused(render(tiny + "--seed -1 " + out()), "--seed must be between 0 and 18446744073709551615 (got -1)");
    expectRefused(render(tiny + "--seed 99999999999999999999 " + out()), "--seed must be between 0 and");
    expectRefused("compare --scene cornell --time 1 --runs 99999999999 --out '" + path("c") + "'",
                  "--runs must be between 1 and 100");
    expectRefused("benchmark --scenes cornell --time 1 --runs 99999999999 --out '" + path("b") + "'",
                  "--runs must be between 2 and 100");
}

// A first word that is no command is named, with the commands and the nearest one to it; no word
// at all lists them. Catches CLI11's "A subcommand is required", which names none.
TEST_F(Cli, AMistypedCommandGetsTheNearestOne) {
    expectRefused("rendr --scene cornell", "unknown command 'rendr' (did you mean 'render'?)");
    expectRefused("benchmrak", "did you mean 'benchmark'?");
    expectRefused("comapre", "did you mean 'compare'?");
    const Outcome far = run("frobnicate");
    EXPECT_EQ(far.exitCode, 1);
    EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << "nothing is near: " << far.err;
    EXPECT_NE(far.err.find("render, scenes, reference, compare, benchmark, export, montage"), std::string::npos)
        << far.err;
    expectRefused("", "a command is required: render, scenes, reference, compare, benchmark, export, montage");
}

// A flag the integrator does not use would be silently ignored, and the user would believe it set:
// each is refused in one line naming the integrators that do use it. In compare, a flag is used if
// any integrator rendering uses it: a method, or the reference's integrator when it renders one.
// Catches each flag accepted with an integrator it does nothing for, and a compare that checks the
// flags against its request's unused default integrator instead of its methods.
TEST_F(Cli, FlagsThatChangeNothingAreRefused) {
    const std::string tiny = "--width 8 --height 8 --spp 1 ";
    expectRefused(render(tiny + "--integrator bdpt --radius 0.1 " + out()), "--radius needs an integrator that merges");
    expectRefused(render(tiny + "--integrator pt --radius-factor 0.1 " + out()), "--radius-factor needs");
    expectRefused(render(tiny + "--integrator lt --radius-pixels 2 " + out()), "--radius-pixels needs");
    expectRefused(render(tiny + "--integrator bdpt --alpha 0.5 " + out()), "--alpha needs an integrator that merges");
    expectRefused(render(tiny + "--integrator pt --light-paths 10 " + out()),
                  "--light-paths needs an integrator that traces light paths (lt, bdpt, vcm, bpm, ppm or auto): pt does not");
    expectRefused(render(tiny + "--integrator mlt --sampler sobol " + out()),
                  "--sampler needs an integrator of independent passes (pt, lt, bdpt, vcm, bpm, ppm or auto): mlt does not");
    expectRefused(render(tiny + "--exposure 2 " + out()), "--exposure requires --png");
    expectRefused(render(tiny + "--exposure nan " + out() + " --png '" + path("out.png") + "'"), "--exposure");
    expectRefused(render(tiny + "--exposure inf " + out() + " --png '" + path("out.png") + "'"), "--exposure");
    EXPECT_FALSE(fs::exists(path("out.png")));
    for (const std::string flags : {"--radius-pixels 2", "--alpha 0.5", "--light-paths 10"}) {
        const Outcome used = run(render(tiny + "--integrator vcm " + flags + " " + out()));
        EXPECT_EQ(used.exitCode, 0) << flags << ": " << used.err;
    }
    EXPECT_EQ(run(render(tiny + "--integrator lt --light-paths 10 " + out())).exitCode, 0);
    for (const std::string integrator : {"pt", "auto"}) {
        const Outcome sobol = run(render(tiny + "--integrator " + integrator + " --sampler sobol " + out()));
        EXPECT_EQ(sobol.exitCode, 0) << integrator << ": " << sobol.err;
    }
    const Outcome exposed = run(render(tiny + "--exposure -2 " + out() + " --png '" + path("out.png") + "'"));
    EXPECT_EQ(exposed.exitCode, 0) << exposed.err;
    fs::remove(path("out.exr"));  // expectRefused checks that none is written

    ASSERT_EQ(run("reference --scene cornell " + tiny + "--out '" + path("ref.exr") + "'").exitCode, 0);
    const std::string compare = "compare --scene cornell --width 8 --height 8 --time 0.05 --out '" + path("c") + "' ";
    const std::string given = "--reference '" + path("ref.exr") + "' ";
    expectRefused(compare + given + "--integrators pt,lt --radius 0.1", "--radius needs an integrator that merges "
                                                                        "(vcm, bpm, ppm or auto): pt, lt do not");
    expectRefused(compare + given + "--integrators pt --light-paths 4", "--light-paths needs");
    const Outcome merging = run(compare + given + "--integrators pt,vcm --radius 0.1");
    EXPECT_EQ(merging.exitCode, 0) << merging.err;
    // Without --reference, the reference is rendered by vcm (the default): the radius is its.
    const Outcome reference = run(compare + "--integrators pt --radius 0.1");
    EXPECT_EQ(reference.exitCode, 0) << reference.err;
}

// CLI11's own parse errors (a number that is not one, an unknown flag) are one line too.
TEST_F(Cli, ParseErrorsAreOneLine) {
    expectRefused(render("--width abc " + out()), "--width");
    expectRefused(render("--no-such-flag " + out()), "--no-such-flag");
    expectRefused(render("--spp 1 --time 1 " + out()), "--time");
}

// A glTF file whose buffer lies outside its folder is refused unless --allow-external-files is
// given, by every command that loads a scene (they share the flag; render and export are tried).
TEST_F(Cli, BufferOutsideTheScenesFolderNeedsAllowExternalFiles) {
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::ofstream(path("triangle.bin"), std::ios::binary).write(reinterpret_cast<const char*>(triangle), sizeof triangle);
    fs::create_directories(path("scene"));
    std::ofstream(path("scene/triangle.gltf")) << R"({"asset":{"version":"2.0"},
        "buffers":[{"byteLength":36,"uri":"../triangle.bin"}],"bufferViews":[{"buffer":0,"byteLength":36}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],
        "materials":[{"emissiveFactor":[1,1,1],"doubleSided":true}],
        "nodes":[{"mesh":0}],"scene":0,"scenes":[{"nodes":[0]}]})";
    const std::string scene = "--scene '" + path("scene/triangle.gltf") + "'";
    const std::string outside = fs::canonical(path("triangle.bin")).string();
    expectRefused("render " + scene + " --spp 1 --width 8 --height 8 " + out(),
                  "buffer 0: uri \"../triangle.bin\" names \"" + outside + "\", outside the scene's folder");
    expectRefused("export " + scene + " --out '" + path("copy.gltf") + "'", "--allow-external-files");
    const Outcome rendered = run("render " + scene + " --allow-external-files --spp 1 --width 8 --height 8 " + out());
    EXPECT_EQ(rendered.exitCode, 0) << rendered.err;
    const Outcome exported = run("export " + scene + " --allow-external-files --out '" + path("copy.gltf") + "'");
    EXPECT_EQ(exported.exitCode, 0) << exported.err;
}

TEST_F(Cli, ExportRefusesBadInput) {
    const Outcome o = run("export --scene contact --out '" + path("contact.gltf") + "'");
    EXPECT_EQ(o.exitCode, 0) << o.err;
    EXPECT_TRUE(fs::exists(path("contact.gltf")));
    expectRefused("export --scene contact --out '" + path("missing/contact.gltf") + "'", "does not exist");
    expectRefused("export --scene contact --out '" + path("contact.obj") + "'", "ends in .gltf or .glb");
    expectRefused("export --scene contact --embed --out '" + path("contact.glb") + "'", "--embed");
    expectRefused("export --scene no-such-scene --out '" + path("x.gltf") + "'", "no-such-scene");
}

// What --out ends in says what export writes: a .glb alone; a .gltf and a .bin of its name beside
// it; with --embed, a .gltf alone.
TEST_F(Cli, ExportWritesAGlbOrAGltfWithItsBin) {
    const Outcome glb = run("export --scene contact --out '" + path("contact.glb") + "'");
    EXPECT_EQ(glb.exitCode, 0) << glb.err;
    std::string magic(4, ' ');
    std::ifstream(path("contact.glb"), std::ios::binary).read(magic.data(), 4);
    EXPECT_EQ(magic, "glTF");
    EXPECT_FALSE(fs::exists(path("contact.bin")));
    const Outcome gltf = run("export --scene contact --out '" + path("contact.gltf") + "'");
    EXPECT_EQ(gltf.exitCode, 0) << gltf.err;
    EXPECT_TRUE(fs::exists(path("contact.bin")));
    EXPECT_NE(gltf.err.find("contact.bin"), std::string::npos) << gltf.err;
    const Outcome embedded = run("export --scene contact --embed --out '" + path("embedded.gltf") + "'");
    EXPECT_EQ(embedded.exitCode, 0) << embedded.err;
    EXPECT_TRUE(fs::exists(path("embedded.gltf")));
    EXPECT_FALSE(fs::exists(path("embedded.bin")));
    const Outcome reloaded = run("export --scene '" + path("contact.glb") + "' --out '" + path("again.gltf") + "'");
    EXPECT_EQ(reloaded.exitCode, 0) << reloaded.err;
}

// A checkpoint is continued only with the settings it was made with (a reference's state, found
// beside a render's output, is refused: its samples came from the reference streams), and a file
// that is not a checkpoint is refused, not trusted. One line, naming the file and what differs.
TEST_F(Cli, ACheckpointIsContinuedOnlyWithItsOwnSettings) {
    const std::string size = "--width 8 --height 8 --spp 4 --checkpoint 100 ";
    ASSERT_EQ(run("reference --scene cornell " + size + "--out '" + path("ref.exr") + "'").exitCode, 0);
    fs::rename(path("ref.exr.checkpoint"), path("out.exr.checkpoint"));
    expectRefused(render(size + out()), "streams=reference");
    std::ofstream(path("out.exr.checkpoint")) << "not a checkpoint\n";
    expectRefused(render(size + out()), "not a tripath checkpoint");
}

// A damaged or edited checkpoint is refused in one line, not continued: a byte flipped in its
// totals (its checksum), a header number that is not all a number in its range (atoi would read
// "-5", "abc", "4x" and 99999999999 somehow), a next-pass whose streams would wrap, seconds that
// are not finite, a state-bytes the file does not hold, another format version. The checkpoint
// as written is continued, so each refusal is the edit's.
TEST_F(Cli, ADamagedCheckpointIsRefused) {
    const std::string reference = "reference --scene cornell --width 8 --height 8 --spp 4 --checkpoint 100 --out '" +
                                  path("ref.exr") + "'";
    ASSERT_EQ(run(reference).exitCode, 0);
    const std::string checkpoint = path("ref.exr.checkpoint"), written = slurp(checkpoint);
    const auto refusedWith = [&](const std::string& text, const std::string& expected) {
        std::ofstream(checkpoint, std::ios::binary) << text;
        expectRefused(reference, expected);
    };
    const auto edited = [&](const std::string& key, const std::string& value) {
        const size_t start = written.find("\n" + key + "=") + 1, end = written.find('\n', start);
        return written.substr(0, start) + key + "=" + value + written.substr(end);
    };
    std::string flipped = written;
    flipped[flipped.size() - 3] ^= 0x10;
    refusedWith(flipped, "the file is damaged");
    for (const char* passes : {"-5", "abc", "4x", "99999999999", ""})
        refusedWith(edited("passes", passes),
                    std::string("passes is '") + passes + "', not a whole number from 0 to 2147483647");
    refusedWith(edited("passes", "5"), "it gives 5 passes, more than its next-pass 4 leaves room for");
    refusedWith(edited("next-pass", "18446744073709551615"), "not a whole number from 0 to 34359738368");
    for (const char* seconds : {"nan", "inf", "-1", "1e300", "0.5s"})
        refusedWith(edited("seconds", seconds),
                    std::string("seconds is '") + seconds + "', not a number from 0 to 1e+09");
    refusedWith(edited("state-bytes", "3000000000"), "its header gives state-bytes=3000000000, but 0 bytes follow");
    refusedWith(written.substr(0, written.size() - 8), "cut short");
    refusedWith("tripath-checkpoint 1" + written.substr(written.find('\n')),
                "written in format '1', this tripath reads format 3");
    std::ofstream(checkpoint, std::ios::binary) << written;
    const Outcome continued = run(reference);
    EXPECT_EQ(continued.exitCode, 0) << continued.err;
    EXPECT_NE(continued.err.find("continuing from"), std::string::npos) << continued.err;
}

// A device or FIFO named as the environment map, the reference or the checkpoint is refused
// without being opened: /dev/zero never ends (the image-format probe looped on it) and a FIFO
// blocks until a writer comes. A refusal takes a moment; 20 s is a hang.
TEST_F(Cli, DevicesAndFifosAreRefusedUnread) {
    const std::string fifo = path("fifo.exr");
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& special : {std::string("/dev/zero"), fifo}) {
        const std::string refusal = "cannot read '" + special + "': not a regular file";
        expectRefused(render("--width 8 --height 8 --spp 1 --environment '" + special + "' " + out()), refusal, 20);
        expectRefused("compare --scene cornell --width 8 --height 8 --time 0.1 --reference '" + special + "' --out '" +
                          path("compared") + "'",
                      refusal, 20);
    }
    ASSERT_EQ(mkfifo(path("out.exr.checkpoint").c_str(), 0600), 0);
    expectRefused(render("--width 8 --height 8 --spp 1 " + out()),
                  "checkpoint '" + path("out.exr.checkpoint") + "': not a regular file", 20);
}

// An output path that names a symbolic link, a device or a FIFO is refused before any rendering,
// and the link and what it names are left as they were: renaming the image over it would have
// replaced the link (or the special file) silently.
TEST_F(Cli, AnOutputThatIsALinkOrASpecialFileIsRefused) {
    { std::ofstream(path("kept.exr")) << "not an image"; }
    fs::create_symlink(path("kept.exr"), path("link.exr"));
    ASSERT_EQ(mkfifo(path("fifo.exr").c_str(), 0600), 0);
    expectRefused("render --scene cornell --width 8 --height 8 --spp 1 --out '" + path("link.exr") + "'",
                  "cannot write '" + path("link.exr") + "': it is a symbolic link, which tripath does not replace");
    expectRefused("render --scene cornell --width 8 --height 8 --spp 1 --out '" + path("fifo.exr") + "'",
                  "cannot write '" + path("fifo.exr") + "': it is a device, FIFO or socket, which tripath does not replace",
                  20);
    EXPECT_TRUE(fs::is_symlink(path("link.exr")));
    EXPECT_EQ(slurp(path("kept.exr")), "not an image");
}

// A reference's numbers are read whole and in range when it is read, before any rendering: its
// spp is not taken as 4 from "4x" (stoi did), its seconds not as NaN, its next-pass not wrapped,
// its dropped-samples not taken from "-1". The file as written is continued.
TEST_F(Cli, AReferencesNumbersAreReadWholeAndInRange) {
    const std::string reference =
        "reference --scene cornell --width 8 --height 8 --spp 2 --out '" + path("ref.exr") + "'";
    ASSERT_EQ(run(reference).exitCode, 0);
    Metadata written;
    const Image image = readExr(path("ref.exr"), &written);
    const auto refusedWith = [&](const std::string& key, const std::string& value, const std::string& expected) {
        Metadata edited = written;
        for (auto& [k, v] : edited)
            if (k == key) v = value;
        writeExr(path("ref.exr"), image, edited);
        expectRefused(reference, "'" + path("ref.exr") + "': " + key + " is '" + value + "', " + expected);
    };
    for (const char* spp : {"4x", "-5", "abc", "99999999999"})
        refusedWith("tripath:spp", spp, "not a whole number from 0 to 2147483647");
    refusedWith("tripath:next-pass", "18446744073709551615", "not a whole number from 0 to 34359738368");
    refusedWith("tripath:dropped-samples", "-1", "not a whole number from 0 to 18446744073709551615");
    for (const char* seconds : {"nan", "-1", "2s"})
        refusedWith("tripath:seconds", seconds, "not a finite number from 0");
    writeExr(path("ref.exr"), image, written);
    EXPECT_EQ(run(reference).exitCode, 0);
}

}  // namespace
}  // namespace tripath
