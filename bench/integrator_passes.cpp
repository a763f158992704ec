// Whole render passes of each integrator on scenes with and without textures: what a textured
// vertex costs, next to the untextured built-ins.
//
//   integrator_pass/<integrator>/<scene>   one pass of render() at 512², max-depth 8, one thread,
//                                          for pt, bdpt, vcm and mlt: samples/s (mlt: chain steps,
//                                          one per pixel, its bootstrap inside the time)
//   integrator_pass/<integrator>-sobol/<scene>  the same for pt, bdpt and vcm under --sampler
//                                          sobol: what drawing scrambled Sobol points costs
//
// The scenes: `cornell` and `veach-mis` (no texture), `sky` (its checkered ground a texture, read
// at every vertex there), and each .gltf or .glb file in TRIPATH_BENCH_GLTF (colon-separated), lit
// by a white sky, e.g. a Khronos sample model textured all over. One thread, and CPU time beside
// the wall clock: the ratios between builds are taken from interleaved runs on a shared machine.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "pass_timing.h"

namespace tripath::bench {

namespace {

constexpr int kDepth = 8;  // the depth bench/README.md states its targets at

void runPass(benchmark::State& state, const std::string& integratorName, const std::string& key, SamplerKind sampler) {
    const Scene& scene = cachedScene(key);
    IntegratorSettings settings;
    settings.walk.maxDepth = kDepth;
    settings.walk.rrDepth = defaultRouletteDepth(integratorName);  // as the front ends render
    timePasses(state, scene, *makeIntegrator(integratorName, settings), 1, sampler);
}

// (label, cache key) of the scenes measured.
std::vector<std::pair<std::string, std::string>> passScenes() {
    std::vector<std::pair<std::string, std::string>> scenes{{"cornell", "cornell"}, {"veach-mis", "veach-mis"}, {"sky", "sky"}};
    if (const char* files = std::getenv("TRIPATH_BENCH_GLTF")) {
        std::istringstream list(files);
        for (std::string file; std::getline(list, file, ':');)
            if (!file.empty()) scenes.push_back({std::filesystem::path(file).stem().string(), file});
    }
    return scenes;
}

const bool registered = [] {
    for (const auto& [label, key] : passScenes())
        for (const char* integrator : {"pt", "bdpt", "vcm", "mlt"})
            for (const SamplerKind sampler : {SamplerKind::Independent, SamplerKind::Sobol}) {
                if (sampler == SamplerKind::Sobol && std::string(integrator) == "mlt") continue;
                const std::string suffix = sampler == SamplerKind::Sobol ? "-sobol" : "";
                registerPasses("integrator_pass/" + std::string(integrator) + suffix + "/" + label,
                               [integrator = std::string(integrator), key = key, sampler](benchmark::State& st) {
                                   runPass(st, integrator, key, sampler);
                               });
            }
    return true;
}();

}  // namespace

}  // namespace tripath::bench
