// `compare` on N ranks: the runs (run-major: run 0 of every method, then run 1, ...) are dealt out
// round-robin, each rendered on one rank alone, and gathered on rank 0, which writes the report.
// Equal-time runs must not share cores: start one rank per core set (docs/distributed.md).
#include "compare.h"

#include <filesystem>

#include "processes.h"
#include "wire.h"

namespace tripath::app {

namespace {

void put(WireWriter& w, const Image& image) { w.put(image.width).put(image.height).put(image.rgb); }
void get(WireReader& r, Image& image) {
    r.get(image.width);
    r.get(image.height);
    r.get(image.rgb);
}

void put(WireWriter& w, const RunOutput& out) {
    w.put(out.run.method).put(out.run.index).put(out.run.seed).put(out.run.checkpoints).put(out.run.stats);
    w.put(out.run.flip);
    put(w, out.image);
    w.put(uint64_t(out.meta.size()));
    for (const auto& [key, value] : out.meta) w.put(key).put(value);
}

RunOutput unpack(WireReader& r) {
    RunOutput out;
    r.get(out.run.method);
    r.get(out.run.index);
    r.get(out.run.seed);
    r.get(out.run.checkpoints);
    r.get(out.run.stats);
    r.get(out.run.flip);
    get(r, out.image);
    uint64_t n = 0;
    r.get(n);
    out.meta.resize(n);
    for (auto& [key, value] : out.meta) r.get(key), r.get(value);
    return out;
}

}  // namespace

std::vector<RunOutput> runEverywhere(const CompareOptions& o, const Scene& scene, const Image& reference, bool allImages) {
    const int ranks = team().size(), me = team().rank();
    const int jobs = o.runs * int(o.methods.size());
    WireWriter mine;
    for (int j = me; j < jobs && !(o.stop && o.stop->load()); j += ranks) {
        RunOutput out = runMethod(o, scene, o.methods[j % o.methods.size()], j / int(o.methods.size()), reference);
        if (out.run.index > 0 && !allImages) out.image = Image{};  // only run 0's images are written; keep messages small
        mine.put(j);
        put(mine, out);
    }
    std::vector<RunOutput> all(jobs);
    for (const std::string& bytes : gather(mine.bytes())) {
        WireReader r(bytes);
        while (!r.done()) {
            int j = 0;
            r.get(j);
            all[j] = unpack(r);
        }
    }
    return all;
}

Reference shareReference(const CompareOptions& o, const Scene& scene) {
    Reference ref;
    together([&] {
        if (o.referencePath.empty() || isRankZero()) ref = obtainReference(o, scene);
    });
    std::string packed = isRankZero() ? packReference(ref) : std::string();
    broadcast(packed);
    if (!isRankZero()) ref = unpackReference(packed);
    return ref;
}

KeptRuns keepRuns(std::vector<RunOutput>& outputs, const std::string& dir) {
    KeptRuns kept;
    for (RunOutput& out : outputs) {
        const std::string& m = out.run.method;
        if (!out.image.rgb.empty()) kept.everyImage[m].push_back(out.image);
        if (out.run.index == 0) {
            writeExr((std::filesystem::path(dir) / (m + ".exr")).string(), out.image, out.meta);
            writePng((std::filesystem::path(dir) / (m + ".png")).string(), out.image);
            kept.images[m] = std::move(out.image);
        }
        kept.runs.push_back(std::move(out.run));
    }
    return kept;
}

std::string packReference(const Reference& ref) {
    WireWriter w;
    put(w, ref.image);
    w.put(ref.description).put(ref.file);
    return w.bytes();
}

Reference unpackReference(const std::string& bytes) {
    WireReader r(bytes);
    Reference ref;
    get(r, ref.image);
    r.get(ref.description);
    r.get(ref.file);
    return ref;
}

}  // namespace tripath::app
