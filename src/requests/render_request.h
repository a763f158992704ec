// What a front end asks to render: the scene, the image size, the integrator and its settings, the
// budget, the seed and the film's extra layers. The command line (apps/) and the Python module
// (python/) fill the same request and it is validated here, in one place, so both refuse the same
// values for the same reasons, and one request gives the same image from either.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/gltf_loader.h"
#include "geometry/scene.h"
#include "image/image.h"
#include "integrators/integrator.h"
#include "integrators/render.h"

namespace tripath {

// The largest image side: --help's limit and validate()'s. Whether a size fits in memory is the
// memory estimate's to say (memory_check.h), not a fixed cap on the pixels.
inline constexpr int kMaxImageSide = 16384;
// The most light paths a pass may trace: as many as the largest image has pixels, the default
// (one per pixel) at that size. What they take is again the memory estimate's to check.
inline constexpr int64_t kMaxLightPaths = int64_t(kMaxImageSide) * kMaxImageSide;

struct RenderRequest {
    std::string scene;                    // a built-in's name or a .gltf/.glb file
    GltfOptions gltf;
    std::string environment;              // a map file or "R,G,B" (environment_spec.h); empty for none
    bool environmentGiven = false;        // given at all: then it may not be empty
    float environmentScale = 1;           // multiplies the environment's radiance
    bool environmentScaleGiven = false;
    std::string integrator = "bdpt";
    int spp = 0;                          // passes (0 unless given: then 16, or as many as `seconds` allows)
    double seconds = 0;                   // wall-clock budget (0 unless given)
    bool sppGiven = false, timeGiven = false, radiusGiven = false, radiusFactorGiven = false;
    int width = 512, height = 512;
    int maxDepth = 16;                    // longest path kept, in segments
    int rrDepth = 0;                      // Russian roulette from this many subpath vertices on; 0: the integrator's default
    std::string mis = "power";            // balance, power or none
    std::string sampler = "sobol";        // sobol or independent (core/sample_stream.h)
    bool samplerGiven = false;
    MergeSettings merge;                  // vcm, bpm, ppm: the radius schedule
    bool radiusPixelsGiven = false, alphaGiven = false;
    int64_t lightPaths = 0;               // light paths per pass, N_L, when lightPathsGiven (else one per pixel); nothing for pt
    bool lightPathsGiven = false;
    MetropolisSettings metropolis;        // mlt: bootstrap, chains, large-step probability
    bool bootstrapGiven = false, chainsGiven = false, largeStepGiven = false;
    uint64_t seed = 1;
    int threads = 0;                      // 0: all cores
    uint64_t memoryLimit = 0;             // bytes the render may take, when memoryLimitGiven (else what the machine has)
    bool memoryLimitGiven = false;
    bool stats = false;                   // run the phase timers (the counts are always kept)
    bool depthImages = false;             // a film layer per path length k = 1..maxDepth
    int strategyImages = 0;               // > 0: weighted and unweighted layers per strategy with k ≤ this
    // The random streams the samples draw from: renders use CameraSample; references Reference, so
    // that a reference and a render with the same seed share no random numbers.
    StreamDomain domain = StreamDomain::CameraSample;
};

// The values an integer parameter may take. validate() refuses others, and the command line checks
// a flag's text against the same range before converting it, so that a number too large for its
// type gets the same message as any other out of range.
struct IntRange {
    int64_t min;
    uint64_t max;
    const char* note = "";  // said after the range: ", 0 for none"
};
inline constexpr IntRange kSizeRange{1, uint64_t(kMaxImageSide)}, kSppRange{1, 1000000}, kMaxDepthRange{1, 1024},
    kRrDepthRange{0, 1024, ", 0 for the integrator's default"}, kThreadsRange{0, 4096, ", 0 for all cores"},
    kLightPathsRange{1, kMaxLightPaths}, kStrategyImagesRange{0, 16, ", 0 for none"}, kSeedRange{0, UINT64_MAX},
    kBootstrapRange{1, 10000000}, kChainsRange{1, 1 << 20};  // the bootstrap keeps 20 bytes a sample
// "--spp must be between 1 and 1000000 (got 0)".
std::string outOfRange(const std::string& name, const IntRange& range, const std::string& got);

// How a front end spells the request's parameters in its messages: "--max-depth" on the command
// line, "max_depth" in Python.
enum class Spelling { CommandLine, Python };
// A parameter named by its command-line flag ("max-depth", "time") as `spelling` writes it:
// "--max-depth", "--time"; "max_depth", "seconds" (Python names every time budget `…seconds`).
std::string parameterName(const char* flag, Spelling spelling);

// Throws InputError, one line naming the parameter as `spelling` writes it, before any work is
// done: for a value out of range (validateValues), an unknown integrator, or a parameter given that
// the integrator does not use (requireUsed).
void validate(const RenderRequest& r, Spelling spelling);
// The values alone, whoever renders them.
void validateValues(const RenderRequest& r, Spelling spelling);
// A parameter given is used by at least one of `integrators` (known names), which render the
// request: a radius or alpha needs one that merges, a light path count one that traces light
// paths, strategy images one with several strategies. A parameter that changes nothing is refused
// rather than ignored, so that nobody believes it set.
void requireUsed(const RenderRequest& r, const std::vector<std::string>& integrators, Spelling spelling);

// The roulette start depth the request renders `integrator` with: rrDepth when given, else that
// integrator's default (defaultRouletteDepth, integrator.h).
int rouletteDepth(const RenderRequest& r, const std::string& integrator);
IntegratorSettings integratorSettings(const RenderRequest& r);
// Budget, seed, threads, timing, streams and layers as the render loop takes them (16 passes
// when neither spp nor seconds is given), and the memory check of the request's budget, whose
// refusal spells the flags to lower as `spelling` does (memory_check.h); one process: a team is
// the caller's to add.
RenderSettings renderSettings(const RenderRequest& r, Spelling spelling = Spelling::CommandLine);
// The scene at the request's image size, its sources (Scene::sources) the scene's then the
// environment's, by its file name; InputError for an unknown name or a bad file.
std::unique_ptr<Scene> loadScene(const RenderRequest& r, const WarningSink& warn = printWarning);

// "render" or "reference", as tripath:streams records a domain.
const char* streamsName(StreamDomain d);
// What decides the image a render converges to, as EXR metadata: tripath:scene-files (the content
// of what `scene` was built from: scene_identity.h), integrator, max-depth, rr-depth ("none" for
// mlt) and mis, and tripath:environment-scale when an environment is given. Every check that a
// file may be added to or measured against (references, checkpoints, the benchmark's reference
// cache) starts from these.
Metadata convergenceSettings(const RenderRequest& r, const Scene& scene, const std::string& integrator);
// The EXR metadata describing a finished render by `ranks` processes: the settings, tripath:scene
// and tripath:environment as the request names them, the counts, tripath:memory-estimate (the
// bytes the render was estimated to need: memory_estimate.h); tripath:interrupted too
// (interruptionText, render.h) when a stop request ended it.
Metadata renderMetadata(const RenderRequest& r, const Scene& scene, const Integrator& integrator, const RenderResult& result,
                        int ranks = 1);
// The part of it that describes the light phase: light paths per pass, and for the merging
// integrators the first pass's radius in world units and alpha (the radius schedule); for mlt,
// its chains' settings (tripath:bootstrap, chains, large-step).
Metadata lightPhaseMetadata(const RenderRequest& r, const Scene& scene, const Integrator& integrator);

}  // namespace tripath
