// libFuzzer target over what a user's file goes through before rendering starts: loadGltf, the
// Scene constructor (validation, emitters, Embree BVH), then one vcm pass on a 4×4 image: its
// light phase (light subpaths, their store and the merge search) and a few camera samples with
// every connection and merge.
//
// Contract under test (docs/design.md §5): any input ends in a SceneDesc or an InputError, never a
// crash, hang, leak or other exception. Anything else escapes this function, and libFuzzer
// reports it with the input that caused it.
//
// Build with -DTRIPATH_FUZZ=ON (clang); run as in scripts/fuzz-gltf.sh. The test suite compiles
// this file too (with any compiler, without libFuzzer): tests/test_fuzz_inputs.cpp calls the
// entry point on every seed and on every fixed crasher kept in tests/data/fuzz/.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

#include "core/error.h"
#include "io/gltf_loader.h"
#include "core/rng.h"
#include "geometry/scene.h"
#include "integrators/integrator.h"
#include "integrators/light_phase.h"

namespace {

// The loader takes a path, so each input is written to a file. Each fuzzing process gets its own
// empty folder: relative buffer URIs in an input then find nothing but the input itself. The
// folder is removed when the process ends normally (the test suite's runs; libFuzzer's rarely do).
class InputFolder {
public:
    InputFolder() : dir_(std::filesystem::temp_directory_path() / ("tripath-fuzz-" + std::to_string(getpid()))) {
        std::filesystem::create_directories(dir_);
    }
    ~InputFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }
    std::string file() const { return (dir_ / "input.gltf").string(); }  // binary or not: the magic bytes say

private:
    std::filesystem::path dir_;
};

const std::string& inputPath() {
    static const InputFolder folder;
    static const std::string path = folder.file();
    return path;
}

class NullSink final : public tripath::ContributionSink {
public:
    void add(tripath::Strategy, const tripath::Connection&) override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string& path = inputPath();
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        if (size > 0) std::fwrite(data, 1, size, f);
        std::fclose(f);
    } else {
        throw std::runtime_error("cannot write the input to " + path);
    }
    const auto silent = [](const std::string&) {};
    try {
        constexpr int kSize = 4;
        const tripath::Scene scene(tripath::loadGltf(path, silent), kSize, kSize, silent);
        // A handful of paths: geometry that passes validation must also be safe to sample.
        tripath::IntegratorSettings settings;
        settings.walk.maxDepth = 4;
        const auto vcm = tripath::makeIntegrator("vcm", settings);
        tripath::LightPhase lightPhase;
        const tripath::Pass pass = lightPhase.run(scene, *vcm, 0, 1, tripath::StreamDomain::Test);
        tripath::PathBuffers paths;
        NullSink sink;
        for (int i = 0; i < kSize; ++i) {  // the diagonal's pixels
            tripath::Rng rng(1, static_cast<uint64_t>(tripath::StreamDomain::Test), static_cast<uint64_t>(i));
            const tripath::Vec2 raster{0.5f + float(i), 0.5f + float(i)};
            vcm->sample(scene, pass, i * (kSize + 1), raster, rng, paths, sink);
        }
    } catch (const tripath::InputError&) {
        // The expected answer to bad input.
    }
    return 0;
}
