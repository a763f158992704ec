// libFuzzer target over the two files a render reads besides its scene, and what each feeds:
//
// - an environment map (--environment; loadEnvironment, requests/environment_spec.h, through
//   OpenImageIO), then its Environment (geometry/environment.h): the sampling distributions built
//   from its texels, the radiance and density of a few directions and, if it has any light, a few
//   samples;
// - a checkpoint (readCheckpoint, requests/checkpoint_file.h), then one pass of the render resumed
//   from it, with the integrator it names, on a 4×4 cornell: the film's totals added in and, for
//   mlt, every chain's saved state read and stepped on.
//
// The first byte chooses (its value mod 5), the rest is the file: 0, 1, 2 an environment map named
// .exr, .hdr or .png (OpenImageIO tries the reader the name gives first, then every other); 3 a
// checkpoint as it is; 4 a checkpoint whose header's checksum line this target rewrites to match
// the rest. A mutation behind the checksum (the totals, the chains' states) otherwise stops at the
// comparison, the last thing the reader does; rewritten, it reaches the code that uses it.
//
// A checkpoint is held to the settings its own header gives (its "tripath:" lines): how a header
// differing from the run's is refused is the command line's test (tests/test_cli.cpp), while here
// any header gets as far as its numbers, totals and the method's state (mlt's chains, auto's
// moments and plans). The resumed render's own settings are
// fixed: max depth 3, and for mlt a bootstrap of 300 samples and one chain per lit length.
//
// The seeds (fuzz/seeds/environment-checkpoint/, each a byte then the file): 4 × 2 to 16 × 8
// skies with a bright texel and a black one, written by OpenImageIO, as EXR in eight compressions
// (tiled, grey and RGBA too), HDR flat and run-length encoded, and PNG of 8 and 16 bits, grey and
// RGBA; and the checkpoints `tripath reference --scene cornell --integrator I --width 4 --height 4
// --max-depth 3 --spp 2 --checkpoint 1000 --threads 1 --out ref.exr` leaves for mlt (with
// --bootstrap 300 --chains 1), bdpt, vcm, pt and auto.
//
// Contract under test: fuzz/targets.h. Build with -DTRIPATH_FUZZ=ON (clang); run as
// `scripts/fuzz-gltf.sh SECONDS environment-checkpoint`.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/fnv1a.h"
#include "geometry/environment.h"
#include "geometry/scene.h"
#include "input_file.h"
#include "integrators/render.h"
#include "requests/checkpoint_file.h"
#include "requests/environment_spec.h"
#include "scenes/builtin_scenes.h"
#include "targets.h"

namespace tripath::fuzz {

namespace {

constexpr int kSize = 4;
const WarningSink silent = [](const std::string&) {};

// The most texels a map may have here: 4096 × 1024, so that reading the largest (its image, its
// texels, their distributions, OpenEXR's chunk buffers) stays far within the fuzzer's memory limit
// (-rss_limit_mb=2048, scripts/fuzz-gltf.sh). With the renderer's own limit (kMaxEnvironmentTexels),
// a map of the most texels costs gigabytes by design, and a crafted file claiming one would be
// reported as running out of memory; the checks that keep a claim within the limit are the same.
constexpr size_t kMaxTexels = size_t(1) << 22;

void sampleEnvironment(const std::string& path) {
    const EnvironmentDesc desc = loadEnvironment(path, 1.0f, silent, kMaxTexels);
    const Environment map(desc.width, desc.height, desc.texels);
    for (const Vec3 d : {Vec3{0, 1, 0}, Vec3{0, -1, 0}, Vec3{0, 0, -1}, Vec3{1, 0, 0}}) {
        map.radiance(d);
        if (map.luminanceIntegral() > 0) map.pdf(d);
    }
    if (map.luminanceIntegral() > 0)
        for (int i = 0; i < 16; ++i) {
            const EnvironmentSample s = map.sample({(float(i % 4) + 0.5f) / 4, (float(i / 4) + 0.5f) / 4});
            map.pdf(s.direction);
            map.radiance(s.direction);
        }
}

// A checkpoint's bytes cut where its reader cuts them: the first line, the header's lines up to
// the blank one, and everything after it. Nothing when there is no blank line (the reader refuses
// such a file as cut short).
struct CheckpointParts {
    std::string_view first;
    std::vector<std::string_view> header;
    std::string_view body;
};

std::optional<CheckpointParts> split(std::string_view file) {
    const size_t firstEnd = file.find('\n');
    if (firstEnd == std::string_view::npos) return std::nullopt;
    const size_t headerEnd = file.find("\n\n", firstEnd);
    if (headerEnd == std::string_view::npos) return std::nullopt;
    CheckpointParts parts{file.substr(0, firstEnd), {}, file.substr(headerEnd + 2)};
    for (size_t start = firstEnd + 1; start <= headerEnd;) {
        const size_t end = file.find('\n', start);
        parts.header.push_back(file.substr(start, end - start));
        start = end + 1;
    }
    return parts;
}

bool isChecksum(std::string_view line) { return line.starts_with("checksum="); }

// The file with every checksum line of its header giving the FNV-1a of its other header lines and
// its body, as writeCheckpoint computes it.
std::string withChecksumRecomputed(std::string_view file) {
    const std::optional<CheckpointParts> parts = split(file);
    if (!parts) return std::string(file);
    Fnv1a sum;
    for (const std::string_view line : parts->header)
        if (!isChecksum(line)) {
            sum.add(line);
            sum.add("\n");
        }
    sum.add(parts->body);
    std::string out = std::string(parts->first) + "\n";
    for (const std::string_view line : parts->header)
        out += (isChecksum(line) ? "checksum=" + hashText(sum.value()) : std::string(line)) + "\n";
    return out + "\n" + std::string(parts->body);
}

// The "tripath:" lines of the file's header, as the settings it must match.
Metadata ownSettings(std::string_view file) {
    Metadata settings;
    if (const std::optional<CheckpointParts> parts = split(file))
        for (const std::string_view line : parts->header)
            if (const size_t eq = line.find('='); line.starts_with("tripath:") && eq != std::string_view::npos)
                settings.emplace_back(line.substr(0, eq), line.substr(eq + 1));
    return settings;
}

std::string valueOf(const Metadata& settings, const std::string& key) {
    for (const auto& [k, v] : settings)
        if (k == key) return v;
    return "";
}

void resumeCheckpoint(const std::string& file) {
    static const Scene scene(builtinScene("cornell"), kSize, kSize, silent);
    const Metadata settings = ownSettings(file);
    const std::optional<RenderResult> saved =
        readCheckpoint(writeInput("input.checkpoint", file), settings, kSize, kSize, FilmLayers{});
    IntegratorSettings is;
    is.walk.maxDepth = 3;
    is.metropolis.bootstrap = 300;
    is.metropolis.chains = 1;
    const auto integrator = makeIntegrator(valueOf(settings, "tripath:integrator"), is);
    RenderSettings rs;
    rs.spp = 1;
    rs.threads = 1;
    rs.resume = &saved.value();  // the file exists: read, or refused
    render(scene, *integrator, rs);
}

}  // namespace

std::string readEnvironmentOrCheckpoint(const uint8_t* data, size_t size) {
    if (size == 0) return "an empty input: no byte to choose a reader by";
    const std::string_view file(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        switch (data[0] % 5) {
            case 0: sampleEnvironment(writeInput("input.exr", file)); break;
            case 1: sampleEnvironment(writeInput("input.hdr", file)); break;
            case 2: sampleEnvironment(writeInput("input.png", file)); break;
            case 3: resumeCheckpoint(std::string(file)); break;
            default: resumeCheckpoint(withChecksumRecomputed(file));
        }
    } catch (const InputError& e) {
        return e.what();  // the expected answer to bad input
    }
    return "";
}

}  // namespace tripath::fuzz

#ifdef TRIPATH_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    tripath::fuzz::readEnvironmentOrCheckpoint(data, size);
    return 0;
}
#endif
