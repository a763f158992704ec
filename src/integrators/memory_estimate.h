// A render's memory, estimated before it allocates its film and its light paths (docs/design.md
// §5): what a front end compares with what the machine has, refusing the render in one line
// rather than letting it die of std::bad_alloc or the kernel's OOM killer after minutes.
//
// The estimate is the process's peak resident memory, in parts: the process itself (its code and
// libraries, measured), the scene as built (Scene::memory: triangles with Embree's BVH, textures,
// environment), the film (Film::images × kBytesPerPixel a pixel, once more for a resumed render's
// film and again for the copy a checkpoint reduces into), what the render loop holds -- a pass's
// light paths, merge search and waiting splats, from a survey of the first pass's own light paths
// (LightPhase::survey), or mlt's chains, splats and bootstrap (metropolisMemory) -- and the
// images written out once the loop has freed what it held. Each part is computed from the sizes
// of the structures that hold it, so a change to one of them moves its part. Against the peak
// resident memory /usr/bin/time measures it is within 10 % from 256² to 2048² for every
// integrator writing a PNG preview, and up to 18 % high without one (docs/memory.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace tripath {

class Scene;
class Integrator;
struct RenderSettings;

struct MemoryPart {
    // When it is held: from before the render to its end, while the render loop runs, or while the
    // results are written (after the loop has freed what it held).
    enum class Phase { Throughout, Rendering, Writing };
    const char* name;    // "film", "light paths", …
    uint64_t bytes = 0;
    // The command-line flags (without "--") that shrink it, "/" joining those that go together
    // ("width/height"); empty when only another scene would ("triangles", "textures").
    std::vector<std::string> lowerWith;
    Phase phase = Phase::Throughout;
};

struct MemoryEstimate {
    std::vector<MemoryPart> parts;  // those above 0 bytes, largest first
    // The parts held throughout, and the larger of those held while rendering and while writing.
    uint64_t total() const;
    // The parts of `more` added, in order of size.
    void add(std::vector<MemoryPart> more);
    // "film 1.50 GiB, light paths 1.10 GiB, …": each part, largest first.
    std::string breakdown() const;
};

// The code and libraries of a tripath process, and what it allocates before it loads a scene:
// 136 to 142 MiB resident on Debian 12 (`tripath scenes`, a 16 × 16 render of cornell).
inline constexpr uint64_t kProcessBytes = uint64_t(140) << 20;
// The images written out, per pixel, at their peak: the float image (12 bytes, all an EXR takes)
// and, for a PNG preview, its clamped copy, OpenImageIO's sRGB conversion and the 8-bit bytes
// (measured: 12 and 35 bytes a pixel over the film, pt at 2048² without and with --png). The
// preview is counted whether or not one is written: the render loop does not know.
inline constexpr uint64_t kOutputBytesPerPixel = 36;

// What holds memory whatever is rendered: the process and the scene.
std::vector<MemoryPart> sceneMemory(const Scene& scene);
// What rendering `scene` with `integrator` and `settings` adds (its layers, a resumed render's
// film, checkpoints): the film, the render loop's parts and the images written. Traces
// LightPhase::kSurveyPaths light paths when the integrator has a light phase: a few milliseconds.
std::vector<MemoryPart> renderMemory(const Scene& scene, const Integrator& integrator, const RenderSettings& settings);
// Both: the estimate of the render.
MemoryEstimate estimateMemory(const Scene& scene, const Integrator& integrator, const RenderSettings& settings);

}  // namespace tripath
