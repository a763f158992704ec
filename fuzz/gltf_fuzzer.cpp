// libFuzzer target over what a user's file goes through before rendering starts: loadGltf, the
// Scene constructor (validation, emitters, Embree BVH) and a few bidirectional samples.
//
// Contract under test (DESIGN.md §5): any input ends in a SceneDesc or an InputError, never a
// crash, hang, leak or other exception. Anything else escapes this function, and libFuzzer
// reports it with the input that caused it.
//
// Build with -DTRIPATH_FUZZ=ON (clang); run as in scripts/fuzz-gltf.sh. Crashers that were fixed
// live in tests/data/fuzz/, where tests/test_stability.cpp loads each one as a regression test.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "geometry/gltf_loader.h"
#include "core/rng.h"
#include "geometry/scene.h"
#include "integrators/integrator.h"

namespace {

// The loader takes a path, so each input is written to a file. Each fuzzing process gets its own
// empty folder: relative buffer URIs in an input then find nothing but the input itself.
const std::string& inputPath() {
    static const std::string path = [] {
        const auto dir = std::filesystem::temp_directory_path() / ("tripath-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(dir);
        return (dir / "input.gltf").string();  // binary or not is decided by the magic bytes
    }();
    return path;
}

class NullSink final : public tripath::ContributionSink {
public:
    void add(int, int, const tripath::Connection&) override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string& path = inputPath();
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        if (size > 0) std::fwrite(data, 1, size, f);
        std::fclose(f);
    } else {
        return 0;
    }
    const auto silent = [](const std::string&) {};
    try {
        const tripath::Scene scene(tripath::loadGltf(path, silent), 4, 4, silent);
        // A handful of paths: geometry that passes validation must also be safe to sample.
        tripath::IntegratorSettings settings;
        settings.walk.maxDepth = 4;
        const auto bdpt = tripath::makeIntegrator("bdpt", settings);
        tripath::PathBuffers paths;
        NullSink sink;
        for (uint64_t i = 0; i < 4; ++i) {
            tripath::Rng rng(1, static_cast<uint64_t>(tripath::StreamDomain::Test), i);
            bdpt->sample(scene, {0.5f + float(i), 0.5f + float(i)}, rng, paths, sink);
        }
    } catch (const tripath::InputError&) {
        // The expected answer to bad input.
    }
    return 0;
}
