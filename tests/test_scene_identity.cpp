// A checkpoint or a reference knows its scene by the content of the files it was built from (the
// glTF, its buffers and images, the environment map: docs/design.md §5), not by the text that
// named them: an edited file is refused where the old samples would be added to or measured
// against, and the same files named another way are the same scene. Runs the built binary.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "image/image.h"
#include "png_bytes.h"
#include "shell_test.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

// Each test starts in a folder holding cornell exported as x.gltf and x.bin, its first material
// textured by t.png, and a 4 x 2 sky.exr.
class SceneIdentity : public test::ShellTest {
protected:
    void SetUp() override {
        ShellTest::SetUp();
        ASSERT_EQ(tripath("export --scene cornell --out x.gltf").exitCode, 0);
        nlohmann::json gltf = nlohmann::json::parse(slurp("x.gltf"));
        gltf["images"] = {{{"uri", "t.png"}}};
        gltf["textures"] = {{{"source", 0}}};
        gltf["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
        save("x.gltf", gltf.dump(2));
        writeTexture(200);
        writeSky(0.5f);
    }

    void writeTexture(uint8_t grey) const {
        test::writePng(path("t.png"), 1, 1, 3, std::vector<uint8_t>{grey, grey, grey});
    }

    // `tripath <args>` run in the test's folder.
    Outcome tripath(const std::string& args) const {
        return shell("cd '" + dir_.string() + "' && '" TRIPATH_BINARY "' " + args);
    }

    void writeSky(float radiance) const {
        Image sky(4, 2);
        for (float& v : sky.rgb) v = radiance;
        writeExr(path("sky.exr"), sky);
    }

    std::string slurp(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
    void save(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
    }

    // Exit code 1 and one line, "error: ..." holding every piece of `expected`.
    static void expectRefused(const Outcome& o, std::initializer_list<std::string> expected) {
        EXPECT_EQ(o.exitCode, 1) << o.err;
        EXPECT_EQ(o.err.rfind("error: ", 0), 0u) << o.err;
        EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
        for (const std::string& piece : expected)
            EXPECT_NE(o.err.find(piece), std::string::npos) << "expected '" << piece << "' in: " << o.err;
    }
};

const std::string kReference = "reference --width 8 --height 8 --spp 2 --checkpoint 100 --out ref.exr ";

// A reference continued from its checkpoint with its scene and sky named x.gltf, ./x.gltf and by
// their absolute paths is, bit for bit, the one render of all its passes.
TEST_F(SceneIdentity, OneSceneNamedThreeWaysContinuesItsCheckpoint) {
    const std::vector<std::string> spellings{"--scene x.gltf --environment sky.exr",
                                             "--scene ./x.gltf --environment ./sky.exr",
                                             "--scene '" + path("x.gltf") + "' --environment '" + path("sky.exr") + "'"};
    for (const std::string& scene : spellings) {
        const Outcome o = tripath(kReference + scene);
        ASSERT_EQ(o.exitCode, 0) << scene << "\n" << o.err;
        if (scene != spellings[0]) {
            EXPECT_NE(o.err.find("continuing from"), std::string::npos) << o.err;
        }
    }
    ASSERT_EQ(tripath("reference --width 8 --height 8 --spp 6 --out whole.exr " + spellings[0]).exitCode, 0);
    EXPECT_EQ(readExr(path("ref.exr")).rgb, readExr(path("whole.exr")).rgb);
}

// An edit to the glTF (a material's colour), to its buffer (a vertex moved by an ulp) or to its
// texture (a texel) between a reference and its continuation is refused, naming the file: by the
// reference's metadata, by its checkpoint alone, and by compare measuring against it. Undone,
// the checkpoint continues.
TEST_F(SceneIdentity, AnEditedSceneFileIsNotContinuedNorMeasuredAgainst) {
    ASSERT_EQ(tripath(kReference + "--scene x.gltf").exitCode, 0);
    const std::string gltf = slurp("x.gltf"), bin = slurp("x.bin"), texture = slurp("t.png"), image = slurp("ref.exr");
    std::string recoloured = gltf;
    const size_t colour = recoloured.find("0.725");
    ASSERT_NE(colour, std::string::npos);
    recoloured.replace(colour, 5, "0.525");
    std::string moved = bin;
    moved[0] ^= 1;  // the first vertex's x, 1.0 → 1.0000001
    const std::string darker = test::pngBytes(1, 1, 3, std::vector<uint8_t>{100, 100, 100});
    const std::map<std::string, std::pair<std::string, std::string>> edits{
        {"x.gltf", {gltf, recoloured}}, {"x.bin", {bin, moved}}, {"t.png", {texture, darker}}};
    for (const auto& [file, versions] : edits) {
        const auto& [original, edited] = versions;
        save(file, edited);
        expectRefused(tripath(kReference + "--scene x.gltf"), {"reference 'ref.exr'", file + " changed"});
        expectRefused(tripath("compare --scene x.gltf --reference ref.exr --width 8 --height 8 --time 0.05 "
                              "--integrators pt --out cmp"),
                      {"reference 'ref.exr'", file + " changed"});
        fs::remove(path("ref.exr"));
        expectRefused(tripath(kReference + "--scene x.gltf"), {"checkpoint 'ref.exr.checkpoint'", file + " changed"});
        save("ref.exr", image);
        save(file, original);
    }
    const Outcome continued = tripath(kReference + "--scene x.gltf");
    EXPECT_EQ(continued.exitCode, 0) << continued.err;
    EXPECT_NE(continued.err.find("continuing from"), std::string::npos) << continued.err;
}

// An environment map edited between a reference and its continuation is refused the same way.
TEST_F(SceneIdentity, AnEditedEnvironmentMapIsNotContinued) {
    const std::string lit = kReference + "--scene cornell --environment sky.exr";
    ASSERT_EQ(tripath(lit).exitCode, 0);
    writeSky(0.6f);
    expectRefused(tripath(lit), {"reference 'ref.exr'", "sky.exr changed"});
    fs::remove(path("ref.exr"));
    expectRefused(tripath(lit), {"checkpoint 'ref.exr.checkpoint'", "sky.exr changed"});
}

// The benchmark's cached reference is reused for the same files however they are named, and
// rendered again once the scene is edited.
TEST_F(SceneIdentity, ACachedReferenceIsNotReusedForAnEditedScene) {
    const std::string benchmark = "benchmark --integrators pt --runs 2 --time 0.02 --reference-time 0.1 --width 8 "
                                  "--height 8 --threads 1 --out bench --scenes ";
    ASSERT_EQ(tripath(benchmark + "x.gltf").exitCode, 0);
    const Outcome again = tripath(benchmark + "'" + path("x.gltf") + "'");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.err.find("reusing the reference"), std::string::npos) << again.err;
    std::string gltf = slurp("x.gltf");
    gltf.replace(gltf.find("0.725"), 5, "0.525");
    save("x.gltf", gltf);
    const Outcome edited = tripath(benchmark + "x.gltf");
    ASSERT_EQ(edited.exitCode, 0) << edited.err;
    EXPECT_NE(edited.err.find("not reusing"), std::string::npos) << edited.err;
    EXPECT_NE(edited.err.find("x.gltf changed"), std::string::npos) << edited.err;
}

}  // namespace
}  // namespace tripath
