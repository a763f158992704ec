// The fuzz target's entry point (fuzz/gltf_fuzzer.cpp, compiled into this suite without libFuzzer)
// on every file it starts from and every crasher it found: the seed corpus of
// scripts/fuzz-gltf.sh (scenes/*.gltf and fuzz/seeds/) and the fixed finds in tests/data/fuzz/
// (README.md there says what each one did). The ordinary build compiles the target, so a change
// of the interfaces it calls breaks this build, not the next fuzzing run; and each input goes
// through exactly what the fuzzer runs: load, Scene, one vcm pass on a few pixels.
//
// The contract is the fuzzer's: the entry point returns normally (the input rendered or was
// refused with an InputError). Any other exception fails the test with its input's name; a crash
// takes down this test's process, which CTest runs on its own, and fails it.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/gltf_loader.h"
#include "geometry/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace tripath {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = TRIPATH_SOURCE_DIR;

std::vector<fs::path> gltfFiles(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(entry.path());
    }
    return files;
}

void feedToTheFuzzTarget(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    ASSERT_TRUE(in) << file;
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_NO_THROW(LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()))
        << file.filename();
}

// The seeds are valid scenes whose buffers are inside the file (data URIs or a .glb's chunk), so
// they load from wherever the entry point writes them and reach its sampling. That they build a
// Scene is checked first: a seed the target refused would pass here without being sampled.
TEST(Fuzz, EntryPointSamplesEverySeed) {
    std::vector<fs::path> seeds = gltfFiles(kSource / "scenes");
    const std::vector<fs::path> more = gltfFiles(kSource / "fuzz" / "seeds");
    seeds.insert(seeds.end(), more.begin(), more.end());
    ASSERT_GE(seeds.size(), 10u);
    const auto silent = [](const std::string&) {};
    for (const fs::path& seed : seeds) {
        EXPECT_NO_THROW(Scene(loadGltf(seed.string(), silent), 4, 4, silent)) << seed.filename();
        feedToTheFuzzTarget(seed);
    }
    RecordProperty("seeds", static_cast<int>(seeds.size()));
}

// Every saved find, fixed since: each crashed, hung or threw something else when it was found.
TEST(Fuzz, EntryPointSurvivesEverySavedFind) {
    const std::vector<fs::path> finds = gltfFiles(kSource / "tests" / "data" / "fuzz");
    ASSERT_GE(finds.size(), 5u);
    for (const fs::path& find : finds) feedToTheFuzzTarget(find);
    RecordProperty("inputs", static_cast<int>(finds.size()));
}

}  // namespace
}  // namespace tripath
