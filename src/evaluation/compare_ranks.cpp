// A comparison on a team of N ranks: the runs (run-major: run 0 of every method, then run 1, ...)
// are dealt out round-robin, each rendered on one rank alone, and gathered on rank 0, which writes
// the report. Equal-time runs must not share cores: start one rank per core set
// (docs/distributed.md). A team of one renders them all in turn.
#include "evaluation/compare.h"

#include "evaluation/wire.h"

namespace tripath::evaluation {

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
    w.put(uint64_t(out.channels.size()));
    for (const ExrChannel& c : out.channels) w.put(c.name).put(c.values);
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
    r.get(n);
    out.channels.resize(n);
    for (ExrChannel& c : out.channels) r.get(c.name), r.get(c.values);
    return out;
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

}  // namespace

std::vector<RunOutput> runEverywhere(const CompareRequest& o, const Scene& scene, const Image& reference, bool allImages) {
    const int ranks = o.team->size(), me = o.team->rank();
    const int jobs = o.runs * int(o.methods.size());
    WireWriter mine;
    for (int j = me; j < jobs && !(o.stop && o.stop->load()); j += ranks) {
        RunOutput out = runMethod(o, scene, o.methods[j % o.methods.size()], j / int(o.methods.size()), reference);
        if (out.run.index > 0 && !allImages) {  // only run 0's images are written; keep messages small
            out.image = Image{};
            out.channels.clear();
        }
        mine.put(j);
        put(mine, out);
    }
    std::vector<RunOutput> all(jobs);
    for (const std::string& bytes : o.team->gather(mine.bytes())) {
        WireReader r(bytes);
        while (!r.done()) {
            int j = 0;
            r.get(j);
            all[j] = unpack(r);
        }
    }
    return all;
}

Reference shareReference(const CompareRequest& o, const Scene& scene) {
    Reference ref;
    const bool rank0 = o.team->rank() == 0;
    // Rendered by every rank together; read or taken from memory by rank 0 alone.
    const bool renders = o.referencePath.empty() && o.referenceImage.rgb.empty();
    together(*o.team, [&] {
        if (renders || rank0) ref = obtainReference(o, scene);
    });
    std::string packed = rank0 ? packReference(ref) : std::string();
    o.team->broadcast(packed);
    if (!rank0) ref = unpackReference(packed);
    return ref;
}

}  // namespace tripath::evaluation
