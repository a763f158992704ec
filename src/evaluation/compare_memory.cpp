// What a comparison holds at its peak (compare.h: comparisonMemory), so that compare() can refuse
// one that does not fit before its first render (docs/memory.md).
#include <algorithm>

#include "evaluation/compare.h"

namespace tripath::evaluation {

namespace {

// The report's bytes per pixel as it draws the side-by-side sheet (the reference and each
// method's image at the comparison's exposure, each method's error map, their Cairo surfaces), the
// crops and the error maps' PNGs: measured at 1024² and 2048², one to three methods, with
// kPerMethod for each method on top of kBase.
constexpr uint64_t kReportBase = 100, kReportPerMethod = 370;

// A finished image as the comparison keeps it: float RGB.
constexpr uint64_t kImageBytesPerPixel = 3 * sizeof(float);

}  // namespace

MemoryEstimate comparisonMemory(const CompareRequest& r, const Scene& scene, bool everyImage) {
    using enum MemoryPart::Phase;
    // The renders run one after another, each freeing what it held before the report: the largest
    // counts, all of it while rendering.
    std::vector<MemoryPart> largest;
    uint64_t largestBytes = 0;
    auto consider = [&](const RenderRequest& request) {
        const auto integrator = makeIntegrator(request.integrator, integratorSettings(request));
        std::vector<MemoryPart> parts = renderMemory(scene, *integrator, renderSettings(request));
        uint64_t bytes = 0;
        for (MemoryPart& p : parts) {
            p.phase = Rendering;
            bytes += p.bytes;
        }
        if (bytes > largestBytes) largest = std::move(parts), largestBytes = bytes;
    };
    const bool rendersReference = r.referencePath.empty() && r.referenceImage.rgb.empty();
    if (rendersReference) consider(referenceRequest(r));
    for (const std::string& method : r.methods) consider(runRequest(r, method, 0));

    const double pixels = double(r.render.width) * r.render.height;
    const size_t kept = 1 + r.methods.size() * size_t(everyImage ? r.runs : 1);
    // auto's run 0 keeps its classes beside its image: four channels of a float (plan_report.h).
    const size_t classBytes = size_t(std::ranges::count(r.methods, "auto")) * 4 * sizeof(float);
    MemoryEstimate e;
    e.add(sceneMemory(scene));
    e.add(std::move(largest));
    e.add({{"images kept", static_cast<uint64_t>(double(kept * kImageBytesPerPixel + classBytes) * pixels), {"width/height"},
            Throughout}});
    if (!r.outDir.empty())
        e.add({{"report",
                static_cast<uint64_t>(double(kReportBase + kReportPerMethod * r.methods.size()) * pixels),
                {"width/height"},
                Writing}});
    return e;
}

}  // namespace tripath::evaluation
