// The fuzz targets' entry points (fuzz/targets.h: fuzz/gltf_fuzzer.cpp and
// fuzz/environment_checkpoint_fuzzer.cpp, compiled into this suite without libFuzzer) on every
// file they start from and every crasher they found: the seed corpora of scripts/fuzz-gltf.sh
// (scenes/*.gltf and fuzz/seeds/gltf/; fuzz/seeds/environment-checkpoint/) and the fixed finds in
// tests/data/fuzz/ (README.md there says what each one did). The ordinary build compiles the
// targets, so a change of the interfaces they call breaks this build, not the next fuzzing run;
// and each input goes through exactly what the fuzzer runs.
//
// The contract is the fuzzer's: the entry point returns normally (the input was used or refused
// with an InputError). Any other exception fails the test with its input's name; a crash takes
// down this test's process, which CTest runs on its own, and fails it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "targets.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = TRIPATH_SOURCE_DIR;

using EntryPoint = std::string (*)(const uint8_t*, size_t);

// The regular files of `dir` whose extension is one of `extensions` (none if there is no `dir`).
std::vector<fs::path> filesIn(const fs::path& dir, const std::vector<std::string>& extensions) {
    std::vector<fs::path> files;
    if (!fs::is_directory(dir)) return files;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file() &&
            std::find(extensions.begin(), extensions.end(), entry.path().extension().string()) != extensions.end())
            files.push_back(entry.path());
    return files;
}

const std::vector<std::string> kGltf{".gltf", ".glb"};
const std::vector<std::string> kInput{".input"};  // the second target's: a byte choosing the reader, then the file
const fs::path kEnvironmentCheckpointSeeds = kSource / "fuzz" / "seeds" / "environment-checkpoint";

std::string bytesOf(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What the entry point answers `bytes`: "" when it used them, else the refusal. Any other exception
// fails the test, naming the file.
std::string feed(EntryPoint target, const std::string& bytes, const fs::path& file) {
    std::string refusal;
    EXPECT_NO_THROW(refusal = target(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size())) << file.filename();
    return refusal;
}

// Every seed is used, not refused: a seed the target refused would seed nothing past the refusal.
// The glTF seeds' buffers are inside the file (data URIs or a .glb's chunk), so they load from
// wherever the entry point writes them and reach its sampling; the second target's seeds are
// environment maps that load and sample and checkpoints that resume.
TEST(Fuzz, EntryPointsUseEverySeed) {
    std::vector<fs::path> seeds = filesIn(kSource / "scenes", kGltf);
    const std::vector<fs::path> more = filesIn(kSource / "fuzz" / "seeds" / "gltf", kGltf);
    seeds.insert(seeds.end(), more.begin(), more.end());
    ASSERT_GE(seeds.size(), 10u);
    for (const fs::path& seed : seeds)
        EXPECT_EQ(feed(fuzz::loadAndSampleGltf, bytesOf(seed), seed), "") << seed.filename();
    const std::vector<fs::path> second = filesIn(kEnvironmentCheckpointSeeds, kInput);
    ASSERT_GE(second.size(), 10u);
    for (const fs::path& seed : second)
        EXPECT_EQ(feed(fuzz::readEnvironmentOrCheckpoint, bytesOf(seed), seed), "") << seed.filename();
    RecordProperty("seeds", static_cast<int>(seeds.size() + second.size()));
}

// The checkpoint target's fifth choice: a checkpoint whose totals were changed is refused by its
// checksum as it is (choice 3), and passes the checksum, to be resumed, once the target rewrites
// the checksum line (choice 4).
TEST(Fuzz, TheRewrittenChecksumLetsAChangedCheckpointThrough) {
    std::string bytes = bytesOf(kEnvironmentCheckpointSeeds / "checkpoint-mlt.input");
    ASSERT_EQ(bytes[0] % 5, 3);
    const size_t totals = bytes.find("\n\n");
    ASSERT_NE(totals, std::string::npos);
    bytes[totals + 2 + 8] ^= 1;  // a low bit of the first value's middle word
    const fs::path name = "checkpoint-mlt.input, a bit flipped";
    EXPECT_NE(feed(fuzz::readEnvironmentOrCheckpoint, bytes, name).find("do not match its checksum"), std::string::npos);
    bytes[0] = 4;
    EXPECT_EQ(feed(fuzz::readEnvironmentOrCheckpoint, bytes, name), "");
}

// Every saved find, fixed since: each crashed, hung or threw something else when it was found.
TEST(Fuzz, EntryPointsSurviveEverySavedFind) {
    const fs::path finds = kSource / "tests" / "data" / "fuzz";
    const std::vector<fs::path> gltf = filesIn(finds, kGltf);
    ASSERT_GE(gltf.size(), 5u);
    for (const fs::path& find : gltf) feed(fuzz::loadAndSampleGltf, bytesOf(find), find);
    const std::vector<fs::path> second = filesIn(finds / "environment-checkpoint", kInput);
    for (const fs::path& find : second) feed(fuzz::readEnvironmentOrCheckpoint, bytesOf(find), find);
    RecordProperty("inputs", static_cast<int>(gltf.size() + second.size()));
}

}  // namespace
}  // namespace tripath
