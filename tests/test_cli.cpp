// The command line under bad input (DESIGN.md §5): every mistake ends with a non-zero exit code and
// one line on stderr saying what is wrong, before any rendering starts, and no output file.
// Each test runs the real binary (TRIPATH_BINARY) through the shell.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/builtin_scenes.h"
#include "geometry/gltf_writer.h"

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

    // Runs `tripath <args>`. `timeout` only keeps a broken build from hanging the suite: a
    // command that starts rendering when it should refuse would run for hours and end with
    // exit code 124, which the tests reject along with every other wrong code.
    Outcome run(const std::string& args) const {
        const std::string out = path("stdout.txt"), err = path("stderr.txt");
        const std::string cmd = "timeout 300 '" TRIPATH_BINARY "' " + args + " >'" + out + "' 2>'" + err + "'";
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
    void expectRefused(const std::string& args, const std::string& expected) const {
        const Outcome o = run(args);
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
    EXPECT_TRUE(fs::exists(path("out.exr")));
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

TEST_F(Cli, HugeResolutionsAreRefused) {
    expectRefused(render("--width 100000 " + out()), "--width");
    expectRefused(render("--height 100000 " + out()), "--height");
    // Each side within limits, but 16384² pixels would need a film of 6 GiB.
    expectRefused(render("--width 16384 --height 16384 " + out()), "--width");
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
    expectRefused(render("--checkpoint nan " + out()), "--checkpoint");
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

TEST_F(Cli, UnknownIntegratorIsRefused) { expectRefused(render("--integrator mlt " + out()), "mlt"); }

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
    expectRefused("export --scene contact --out '" + path("contact.glb") + "'", ".gltf");
    expectRefused("export --scene no-such-scene --out '" + path("x.gltf") + "'", "no-such-scene");
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

}  // namespace
}  // namespace tripath
