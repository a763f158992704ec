// libFuzzer target over what a user's file goes through before rendering starts: loadGltf, the
// Scene constructor (validation, emitters, Embree BVH), then one vcm pass on a 4×4 image: its
// light phase (light subpaths, their store and the merge search) and a few camera samples with
// every connection and merge.
//
// Contract under test (docs/design.md §5, fuzz/targets.h): any input ends in a sampled Scene or an
// InputError, never a crash, hang, leak or other exception. Anything else escapes this function,
// and libFuzzer reports it with the input that caused it.
//
// Build with -DTRIPATH_FUZZ=ON (clang); run as in scripts/fuzz-gltf.sh. The test suite compiles
// this file too (with any compiler, without libFuzzer): tests/test_fuzz_inputs.cpp calls the
// entry point on every seed and on every fixed crasher kept in tests/data/fuzz/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/gltf_loader.h"
#include "core/rng.h"
#include "geometry/scene.h"
#include "integrators/pixel_sample_integrator.h"
#include "integrators/light_phase.h"
#include "input_file.h"
#include "targets.h"

namespace tripath::fuzz {

namespace {

class NullSink final : public ContributionSink {
public:
    void add(Strategy, const Connection&) override {}
};

}  // namespace

std::string loadAndSampleGltf(const uint8_t* data, size_t size) {
    // Named .gltf, binary or not: the loader goes by the magic bytes.
    const std::string path = writeInput("input.gltf", {reinterpret_cast<const char*>(data), size});
    const auto silent = [](const std::string&) {};
    try {
        constexpr int kSize = 4;
        const Scene scene(loadGltf(path, silent), kSize, kSize, silent);
        // A handful of paths: geometry that passes validation must also be safe to sample.
        IntegratorSettings settings;
        settings.walk.maxDepth = 4;
        const auto integrator = makeIntegrator("vcm", settings);
        const PixelSampleIntegrator& vcm = *integrator->pixelSamples();
        LightPhase lightPhase;
        const Pass pass = lightPhase.run(scene, vcm, 0, {1, StreamDomain::Test});
        PathBuffers paths;
        NullSink sink;
        for (int i = 0; i < kSize; ++i) {  // the diagonal's pixels
            SampleStream rng(SamplerKind::Independent, 1, StreamDomain::Test, uint64_t(i), 0,
                             Rng(1, static_cast<uint64_t>(StreamDomain::Test), static_cast<uint64_t>(i)));
            const Vec2 raster{0.5f + float(i), 0.5f + float(i)};
            vcm.sample(scene, pass, i * (kSize + 1), raster, rng, paths, sink);
        }
    } catch (const InputError& e) {
        return e.what();  // the expected answer to bad input
    }
    return "";
}

}  // namespace tripath::fuzz

#ifdef TRIPATH_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    tripath::fuzz::loadAndSampleGltf(data, size);
    return 0;
}
#endif
