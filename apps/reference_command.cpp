// `tripath reference`: a long render to measure other renders against. Run again on its own
// output with the same settings, it adds fresh samples instead of starting over, so a reference
// can be refined over several sessions.
//
// A reference draws its samples from its own stream domain (StreamDomain::Reference, recorded as
// tripath:streams=reference), not from the one renders use: `tripath reference` and `tripath
// render`/`compare` with the same --seed (by default both 1) share no random numbers, so the
// defaults work together and compare need not refuse them.
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <iostream>

#include "checkpoint.h"
#include "commands.h"
#include "geometry/embree_isa.h"
#include "core/error.h"
#include "image/exposure.h"
#include "processes.h"
#include "evaluation/reference_file.h"
#include "render_options.h"

namespace tripath::app {

namespace {

using evaluation::readReference;
using evaluation::ReferenceFile;
using evaluation::setMetadata;

struct ReferenceCommand {
    RenderOptions options;
    std::string out, png;
};

// The settings that must match for new samples to estimate the same image as the old ones
// (the seed too: the new passes continue the old sample indices, so only the same seed keeps
// them fresh).
Metadata settingsToMatch(const RenderOptions& o, const Scene& scene, const std::string& integrator) {
    Metadata m = convergenceSettings(o, scene, integrator);
    m.push_back({"tripath:seed", std::to_string(o.seed)});
    return m;
}

// The reference already at --out, checked against this run's settings and scene; nullopt if there
// is none.
std::optional<ReferenceFile> previous(const ReferenceCommand& c, const Scene& scene, const Integrator& integrator) {
    if (!std::filesystem::exists(c.out)) return std::nullopt;
    ReferenceFile ref = readReference(c.out);
    requireSettings(ref, settingsToMatch(c.options, scene, integrator.name()), false);
    // Samples from another Embree version or ISA may hit differently (embree_isa.h): never mixed.
    requireSettings(ref, {{"tripath:embree", embreeDescription()}}, true);
    requireSize(ref, c.options.width, c.options.height);
    if (ref.spp() < 1) throw InputError(fmt::format("'{}' records {} spp: nothing to add to", c.out, ref.spp()));
    // A merging reference continues its radius schedule from the passes in the file (the pass
    // index runs on): the schedule must be the same one. (Files from before the light phase
    // lack these keys; they are bdpt or lt references, whose added passes need no schedule.)
    requireSettings(ref, lightPhaseMetadata(c.options, scene, integrator), true);
    return ref;
}

// The average of all passes from the two averages and their pass counts, in double.
Image combine(const Image& a, int passesA, const Image& b, int passesB) {
    Image out(a.width, a.height);
    const double total = double(passesA) + passesB;
    for (size_t i = 0; i < out.rgb.size(); ++i)
        out.rgb[i] = static_cast<float>((double(a.rgb[i]) * passesA + double(b.rgb[i]) * passesB) / total);
    return out;
}

void validate(const ReferenceCommand& c) {
    validateRenderOptions(c.options);
    if (!c.options.sppGiven && !c.options.timeGiven) throw InputError("reference needs a budget: --spp N or --time SECONDS");
    if (std::filesystem::path(c.out).extension() != ".exr") throw InputError("--out must name an .exr file: " + c.out);
    if (!c.png.empty() && std::filesystem::path(c.png).extension() != ".png")
        throw InputError("--png must name a .png file: " + c.png);
    if (!isRankZero()) return;  // only rank 0 writes
    checkWritable(c.out);
    if (!c.png.empty()) checkWritable(c.png);
}

// The first pass index the file's samples left unused (tripath:next-pass; files from before it
// used passes 0 .. spp−1).
uint64_t nextPass(const ReferenceFile& ref) {
    return ref.wholeNumber("tripath:next-pass", kMaxFirstPass, uint64_t(ref.spp()));
}

void run(const ReferenceCommand& c) {
    RenderOptions o = c.options;
    const auto integrator = makeIntegrator(o.integrator, integratorSettings(o));
    // Rank 0 reads what is already at --out; a checkpoint beside it is continued exactly
    // (renderResumable), a reference without one by averaging in the new passes.
    std::optional<ReferenceFile> old;
    bool exact = false;
    std::unique_ptr<Scene> scene;
    together([&] {
        validate(c);
        scene = loadScene(o);
        if (isRankZero()) old = previous(c, *scene, *integrator);
        exact = old && std::filesystem::exists(checkpointPath(c.out));
    });
    // The others learn the streams and the pass to start from.
    std::array<uint64_t, 3> shared{old ? 1u : 0u, old ? uint64_t(streamDomain(*old)) : 0, old ? nextPass(*old) : 0};
    team().max(shared);
    const bool continuing = shared[0] != 0;
    // New files use the reference streams; added samples continue in the streams of the file
    // (a reference written before tripath:streams existed drew from the render streams).
    o.domain = continuing ? static_cast<StreamDomain>(shared[1]) : StreamDomain::Reference;

    RenderSettings rs = renderSettings(o);
    rs.team = &team();
    rs.firstPass = continuing ? shared[2] : 0;  // fresh sample indices after the ones already in the file
    rs.stop = installInterruptHandler();
    const std::string label = fmt::format("reference {} {}", o.integrator, o.scene);
    rs.progress = progressReporter(rs, o.width, o.height, label);
    Resumable how{c.out, checkpointSettings(o, *scene, *integrator, rs.layers), false, true, {}};
    how.writeImage = [&](const RenderResult& sofar) {
        writeExr(c.out, sofar.image(), renderMetadata(o, *scene, *integrator, sofar, team().size()));
    };
    const RenderResult r = renderResumable(*scene, *integrator, rs, o, how);
    if (!isRankZero()) return;
    printSummary(label, r, o);
    if (r.interruptedBeforeAnyPass) return;  // nothing to write, as the summary said

    Metadata meta = renderMetadata(o, *scene, *integrator, r, team().size());
    Image image = r.image();
    if (old && !exact) {
        image = combine(old->image, old->spp(), image, r.passes);
        const int spp = old->spp() + r.passes;
        const double seconds = old->seconds() + r.seconds;
        const uint64_t dropped = old->wholeNumber("tripath:dropped-samples", UINT64_MAX, 0) + r.droppedSamples;
        setMetadata(meta, "tripath:spp", std::to_string(spp));
        setMetadata(meta, "tripath:seconds", fmt::format("{:.3f}", seconds));
        setMetadata(meta, "tripath:dropped-samples", std::to_string(dropped));
        std::cerr << fmt::format("added {} spp to the {} spp in {}: {} spp, {:.1f} s in all\n", r.passes, old->spp(),
                                 c.out, spp, seconds);
    }
    writeExr(c.out, image, meta);
    if (!c.png.empty()) writePreviewPng(c.png, image, std::nullopt);
    std::cerr << "wrote " << c.out << (c.png.empty() ? "" : " and " + c.png) << "\n";
}

}  // namespace

void addReferenceCommand(CLI::App& app) {
    auto c = std::make_shared<ReferenceCommand>();
    auto* cmd = app.add_subcommand(
        "reference",
        "Render a reference image for `tripath compare`; run again on an existing reference with the same settings "
        "to add samples to it");
    addRenderOptions(*cmd, c->options);
    cmd->get_option("--seed")->description(
        "Seed of the reference's own random streams: a reference never shares samples with a render or compare "
        "run, whatever their --seed (the EXR records tripath:streams=reference)");
    cmd->add_option("--out", c->out,
                    "Reference EXR. If it exists (same scene, integrator, size, max depth, RR depth, MIS and seed), "
                    "the new samples are added to it and its spp and seconds become the totals")
        ->required();
    cmd->add_option("--png", c->png,
                    "Also write an sRGB PNG preview of the (combined) reference here, exposed from the image as "
                    "render's --png is without --exposure");
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
