// `tripath render`: one image of a scene with one integrator, to EXR (and a PNG preview).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "checkpoint.h"
#include "commands.h"
#include "geometry/error.h"
#include "processes.h"
#include "render_options.h"

namespace tripath::app {

namespace {

struct RenderCommand {
    RenderOptions options;
    std::string out, png;
    float exposure = 0;
    bool depthImages = false;
    int strategyImages = 0;
};

// "<dir>/<stem><suffix>.exr" beside the main output.
std::string sibling(const std::string& out, const std::string& suffix) {
    const std::filesystem::path p(out);
    return (p.parent_path() / (p.stem().string() + suffix + ".exr")).string();
}

void validate(const RenderCommand& c) {
    const RenderOptions& o = c.options;
    validateRenderOptions(o);
    if (std::filesystem::path(c.out).extension() != ".exr") throw InputError("--out must name an .exr file: " + c.out);
    if (!c.png.empty() && std::filesystem::path(c.png).extension() != ".png")
        throw InputError("--png must name a .png file: " + c.png);
    if (c.strategyImages < 0 || c.strategyImages > 16)
        throw InputError(fmt::format("--strategy-images must be between 1 and 16 (got {})", c.strategyImages));
    if (c.strategyImages > 0 && (o.integrator == "pt" || o.integrator == "lt"))
        throw InputError("--strategy-images needs --integrator bdpt, vcm, bpm or ppm (pt and lt have no (s,t) to separate)");
    if (!isRankZero()) return;  // only rank 0 writes
    checkWritable(c.out);
    if (!c.png.empty()) checkWritable(c.png);
}

void write(const RenderCommand& c, const RenderSettings& rs, const Metadata& meta, const RenderResult& r) {
    writeExr(c.out, r.image(), meta);
    if (!c.png.empty()) writePng(c.png, r.image(), c.exposure);
    for (int k = 1; k <= rs.layers.depthImages; ++k) writeExr(sibling(c.out, fmt::format("-k{}", k)), r.film.depthImage(k, r.passes), meta);
    for (const Strategy& st : r.film.strategies()) {
        const std::string name = fmt::format("-s{}-t{}{}", st.s, st.t, st.merge ? "-merge" : "");
        writeExr(sibling(c.out, name + "-weighted"), r.film.strategyImage(st, true, r.passes), meta);
        writeExr(sibling(c.out, name + "-unweighted"), r.film.strategyImage(st, false, r.passes), meta);
    }
}

void run(const RenderCommand& c) {
    const RenderOptions& o = c.options;
    std::unique_ptr<Scene> scene;
    together([&] {
        validate(c);
        scene = loadScene(o);
    });
    const auto integrator = makeIntegrator(o.integrator, integratorSettings(o));
    RenderSettings rs = renderSettings(o);
    if (c.depthImages) rs.layers.depthImages = o.maxDepth;
    rs.layers.strategyLength = c.strategyImages;
    rs.stop = installInterruptHandler();
    const std::string label = fmt::format("{} {}", o.integrator, o.scene);
    rs.progress = progressReporter(rs, o.width, o.height, label);

    Resumable how{c.out, checkpointSettings(o, *scene, *integrator, rs.layers), true, false, {}};
    how.writeImage = [&](const RenderResult& sofar) { write(c, rs, renderMetadata(o, *scene, *integrator, sofar), sofar); };
    const RenderResult r = renderResumable(*scene, *integrator, rs, o, how);
    if (!isRankZero()) return;
    printSummary(label, r, o);
    write(c, rs, renderMetadata(o, *scene, *integrator, r), r);
    std::cerr << "wrote " << c.out << (c.png.empty() ? "" : " and " + c.png) << "\n";
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto c = std::make_shared<RenderCommand>();
    auto* cmd = app.add_subcommand("render", "Render a scene with one integrator to a linear EXR (and a PNG preview)");
    addRenderOptions(*cmd, c->options);
    cmd->add_option("--out", c->out, "Output EXR: linear radiance, 32-bit float, with the settings as metadata")->required();
    cmd->add_option("--png", c->png, "Also write an sRGB PNG preview here");
    cmd->add_option("--exposure", c->exposure, "PNG exposure in stops (the EXR is never scaled)")->capture_default_str();
    cmd->add_flag("--depth-images", c->depthImages,
                  "Also write <out>-k<K>.exr for each path length K = 1..max-depth: the Neumann-series terms, which "
                  "add up to the full image");
    cmd->add_option("--strategy-images", c->strategyImages,
                    "bdpt, vcm, bpm, ppm: also write <out>-s<S>-t<T>-weighted.exr and -unweighted.exr for every "
                    "connection (s,t) of path length k <= this value (k = s+t-1), and <out>-s<S>-t<T>-merge-*.exr for "
                    "every merge (k = s+t-2)");
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
