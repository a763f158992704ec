// A comparison from request to result: the checks that can fail before anything renders, then the
// reference, the runs on every rank, the reduction to curves and summaries, and the report.
#include "evaluation/compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/exposure.h"
#include "image/font.h"
#include "requests/memory_check.h"

namespace tripath::evaluation {

namespace fs = std::filesystem;

namespace {

// The rendered methods and, when the comparison renders its reference, its integrator.
std::vector<std::string> renderingIntegrators(const CompareRequest& r) {
    std::vector<std::string> all = r.methods;
    if (r.referencePath.empty() && r.referenceImage.rgb.empty()) all.push_back(r.referenceIntegrator);
    return all;
}

// Run 0's images and channels (also written as <dir>/<method>.exr and .png, at the comparison's
// exposure, when there is a directory), and every image the outputs carry, by method in run order.
void keepRuns(std::vector<RunOutput>& outputs, const std::string& dir, Comparison& c) {
    for (RunOutput& out : outputs) {
        const std::string& m = out.run.method;
        if (!out.image.rgb.empty()) c.everyImage[m].push_back(out.image);
        if (out.run.index == 0) {
            if (!dir.empty()) {
                writeExr((fs::path(dir) / (m + ".exr")).string(), out.image, out.meta, out.channels);
                writePng((fs::path(dir) / (m + ".png")).string(), out.image, c.exposureStops);
            }
            c.images[m] = std::move(out.image);
            if (!out.channels.empty()) c.channels[m] = std::move(out.channels);
        }
        c.runs.push_back(std::move(out.run));
    }
}

}  // namespace

void checkList(const std::vector<std::string>& items, const char* flag, Spelling spelling,
               const std::function<void(const std::string&)>& known, bool mayBeEmpty) {
    const std::string name = parameterName(flag, spelling);
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].empty()) throw InputError(fmt::format("{} has an empty entry", name));
        if (known) known(items[i]);
        if (std::find(items.begin(), items.begin() + i, items[i]) != items.begin() + i)
            throw InputError(fmt::format("{} lists '{}' twice", name, items[i].substr(0, 40)));
    }
    if (items.empty() && !mayBeEmpty) throw InputError(fmt::format("{} needs at least one entry", name));
}

void checkOutDir(const std::string& dir, const std::string& file, Spelling spelling) {
    const std::string name = parameterName("out", spelling);
    std::error_code ec;
    if (fs::exists(dir, ec)) {
        if (!fs::is_directory(dir, ec)) throw InputError(fmt::format("{} '{}' exists and is not a directory", name, dir));
        checkWritable((fs::path(dir) / file).string());
        return;
    }
    // The nearest folder that exists must let the missing ones be made in it.
    fs::path missing = fs::absolute(dir, ec).lexically_normal();
    while (!missing.parent_path().empty() && missing.parent_path() != missing && !fs::exists(missing.parent_path(), ec))
        missing = missing.parent_path();
    if (!fs::is_directory(missing.parent_path(), ec))
        throw InputError(fmt::format("cannot create {} directory '{}': '{}' is not a directory", name, dir,
                                     missing.parent_path().string()));
    checkWritable(missing.string());
}

void createDirectory(const std::string& dir) {
    if (dir.empty()) return;  // the current folder
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError(fmt::format("cannot create directory '{}': {}", dir, ec.message()));
}


void validate(const CompareRequest& r, Spelling spelling) {
    auto name = [spelling](const char* flag) { return parameterName(flag, spelling); };
    validateValues(r.render, spelling);
    if (!(r.render.seconds > 0)) throw InputError(name("time") + " must be more than 0 seconds");
    if (r.runs < kRunsRange.min || uint64_t(r.runs) > kRunsRange.max)
        throw InputError(outOfRange(name("runs"), kRunsRange, std::to_string(r.runs)));
    if (r.referenceSeconds < 0)
        throw InputError(fmt::format("{} must be above 0 (got {})", name("reference-time"), r.referenceSeconds));
    checkList(r.methods, "integrators", spelling, [](const std::string& m) { makeIntegrator(m, {}); });
    makeIntegrator(r.referenceIntegrator, {});  // an unknown name is refused before anything renders
    requireUsed(r.render, renderingIntegrators(r), spelling);
    if (const auto& c = r.crop;
        c && (c->w <= 0 || c->h <= 0 || c->x < 0 || c->y < 0 || c->x > r.render.width - c->w || c->y > r.render.height - c->h))
        throw InputError(fmt::format("{} {},{},{},{} is not inside the {}x{} image", name("crop"), c->x, c->y, c->w, c->h,
                                     r.render.width, r.render.height));
    checkList(r.sheetFormats, "formats", spelling, [&](const std::string& f) {
        if (std::find(kSheetFormats.begin(), kSheetFormats.end(), f) == kSheetFormats.end())
            throw InputError(fmt::format("{} takes png, pdf and svg (got '{}')", name("formats"), f.substr(0, 20)));
    }, true);
    if (!r.referenceImage.rgb.empty() &&
        (r.referenceImage.width != r.render.width || r.referenceImage.height != r.render.height))
        throw InputError(fmt::format("the reference is {}x{}, the renders {}x{}", r.referenceImage.width,
                                     r.referenceImage.height, r.render.width, r.render.height));
    if (r.team->rank() != 0) return;  // rank 0 alone reads the reference file and writes the report
    if (!r.referencePath.empty() && !fs::exists(r.referencePath))
        throw InputError(fmt::format("cannot read reference '{}': file does not exist", r.referencePath));
    if (r.outDir.empty()) return;
    requireFont();
    checkOutDir(r.outDir, "error.csv", spelling);
}

Comparison compare(const CompareRequest& r, const Scene& scene, bool everyImage) {
    together(*r.team, [&] { requireMemory(comparisonMemory(r, scene, everyImage), memoryLimit(r.render), r.spelling); });
    Comparison c;
    c.reference = shareReference(r, scene);
    std::vector<RunOutput> outputs = runEverywhere(r, scene, c.reference.image, everyImage);
    c.interrupted = r.stop && r.stop->load();
    if (r.team->rank() != 0 || c.interrupted) return c;
    c.exposureStops = autoExposureStops(c.reference.image);
    if (!r.outDir.empty()) {
        createDirectory(r.outDir);
        writePng((fs::path(r.outDir) / "reference.png").string(), c.reference.image, c.exposureStops);
    }
    keepRuns(outputs, r.outDir, c);
    for (const std::string& m : r.methods) c.curves.push_back(curveOf(c.runs, m));
    c.summaries = summarize(c.runs, c.curves);
    if (!r.outDir.empty()) writeReport(r, c, r.outDir);
    return c;
}

}  // namespace tripath::evaluation
