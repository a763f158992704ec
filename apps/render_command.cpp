// `tripath render`: one image of a scene with one integrator, to EXR (and a PNG preview).
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

#include "checkpoint.h"
#include "commands.h"
#include "core/error.h"
#include "image/exposure.h"
#include "processes.h"
#include "render_options.h"

namespace tripath::app {

namespace {

struct RenderCommand {
    RenderOptions options;
    std::string out, png;
    std::string replay;  // --replay PASS,PIXEL
    std::optional<float> exposure;  // none: exposed from the image (image/exposure.h)
};

// The PNG's exposure in stops goes up to 2^±64, past any radiance a scene gives (and NaN is refused).
constexpr float kMaxExposure = 64;

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
    if (c.exposure && !(std::abs(*c.exposure) <= kMaxExposure))
        throw InputError(fmt::format("--exposure must be a number of stops between -{0} and {0} (got {1})", kMaxExposure,
                                     *c.exposure));
    if (!isRankZero()) return;  // only rank 0 writes
    checkWritable(c.out);
    if (!c.png.empty()) checkWritable(c.png);
}

void write(const RenderCommand& c, const RenderSettings& rs, const Metadata& meta, const RenderResult& r) {
    writeExr(c.out, r.image(), meta, classChannels(r.plans, r.film.width(), r.film.height()));
    if (!c.png.empty()) writePreviewPng(c.png, r.image(), c.exposure);
    for (int k = 1; k <= rs.layers.depthImages; ++k) writeExr(sibling(c.out, fmt::format("-k{}", k)), r.film.depthImage(k, r.passes), meta);
    for (const Strategy& st : r.film.strategies()) {
        const std::string name = fmt::format("-s{}-t{}{}", st.s, st.t, st.merge ? "-merge" : "");
        writeExr(sibling(c.out, name + "-weighted"), r.film.strategyImage(st, true, r.passes), meta);
        writeExr(sibling(c.out, name + "-unweighted"), r.film.strategyImage(st, false, r.passes), meta);
    }
}

// --replay: one sample's contributions, one line each, on stdout.
class PrintingSink final : public ContributionSink {
public:
    void add(Strategy st, const Connection& c) override {
        const Spectrum w = c.weighted();
        const bool finite = isFinite(w) && isFinite(c.unweighted);
        std::cout << fmt::format("s={} t={} {} k={}: f/p = ({:.6g}, {:.6g}, {:.6g}) x weight {:.6g} = ({:.6g}, {:.6g}, {:.6g})",
                                 st.s, st.t, st.merge ? "merge" : "connect", st.length(), c.unweighted.x, c.unweighted.y,
                                 c.unweighted.z, c.weight, w.x, w.y, w.z);
        if (c.raster)
            std::cout << fmt::format(", splat at pixel ({:.2f}, {:.2f}) (the film adds it times 1/N_L)", c.raster->x, c.raster->y);
        if (c.weightGuarded) std::cout << ", weight guarded to 0 (a pdf ratio was not finite)";
        if (!finite) std::cout << "  <- NOT FINITE: the film drops this sample";
        std::cout << "\n";
        if (finite && !c.raster) sum_ = sum_ + w;
        ++count_;
    }
    void summarize() const {
        std::cout << fmt::format("{} contributions; the finite ones to the sample's own pixel add up to ({:.6g}, {:.6g}, {:.6g})\n",
                                 count_, sum_.x, sum_.y, sum_.z);
    }

private:
    Spectrum sum_{0.0f};
    int count_ = 0;
};

// "PASS,PIXEL" as two non-negative integers, the pixel inside the image.
std::pair<uint64_t, int> parseReplay(const std::string& text, int width, int height) {
    uint64_t pass = 0, pixel = 0;
    const char *begin = text.data(), *end = begin + text.size();
    const auto [afterPass, passError] = std::from_chars(begin, end, pass);
    const bool ok = passError == std::errc{} && afterPass != end && *afterPass == ',' &&
                    std::from_chars(afterPass + 1, end, pixel) == std::from_chars_result{end, std::errc{}} &&
                    pixel < uint64_t(width) * uint64_t(height);
    if (!ok)
        throw InputError(fmt::format("--replay must be PASS,PIXEL with PIXEL = y * width + x below {} (got '{}')",
                                     uint64_t(width) * uint64_t(height), text));
    return {pass, int(pixel)};
}

void replay(const RenderCommand& c) {
    const RenderOptions& o = c.options;
    validateRenderOptions(o);
    const auto [pass, pixel] = parseReplay(c.replay, o.width, o.height);
    const auto integrator = makeIntegrator(o.integrator, integratorSettings(o));
    const PixelSampleIntegrator* samples = integrator->pixelSamples();
    if (!samples)
        throw InputError(fmt::format("--replay renders a pixel's sample again; {} has no pixel samples", o.integrator));
    const auto scene = loadScene(o);
    std::cout << fmt::format("{} {}, seed {}: pass {}, {} {} (x {}, y {})\n", o.integrator, o.scene, o.seed, pass,
                             o.integrator == "lt" ? "light path" : "pixel", pixel, pixel % o.width, pixel / o.width);
    PrintingSink sink;
    replaySample(*scene, *samples, renderSettings(o), pass, pixel, sink);  // one process replays
    sink.summarize();
}

void run(const RenderCommand& c) {
    if (!c.replay.empty()) return replay(c);
    const RenderOptions& o = c.options;
    std::unique_ptr<Scene> scene;
    together([&] {
        validate(c);
        scene = loadScene(o);
    });
    const auto integrator = makeIntegrator(o.integrator, integratorSettings(o));
    RenderSettings rs = renderSettings(o);
    rs.team = &team();
    rs.stop = installInterruptHandler();
    const std::string label = fmt::format("{} {}", o.integrator, o.scene);
    rs.progress = progressReporter(rs, o.width, o.height, label);

    Resumable how{c.out, checkpointSettings(o, *scene, *integrator, rs.layers), true, false, {}};
    how.writeImage = [&](const RenderResult& sofar) {
        write(c, rs, renderMetadata(o, *scene, *integrator, sofar, team().size()), sofar);
    };
    const RenderResult r = renderResumable(*scene, *integrator, rs, o, how);
    if (!isRankZero()) return;
    printSummary(label, r, o);
    if (r.interruptedBeforeAnyPass) return;  // nothing to write, as the summary said
    write(c, rs, renderMetadata(o, *scene, *integrator, r, team().size()), r);
    std::cerr << "wrote " << c.out << (c.png.empty() ? "" : " and " + c.png) << "\n";
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto c = std::make_shared<RenderCommand>();
    auto* cmd = app.add_subcommand("render", "Render a scene with one integrator to a linear EXR (and a PNG preview)");
    addRenderOptions(*cmd, c->options);
    cmd->add_option("--out", c->out, "Output EXR: linear radiance, 32-bit float, with the settings as metadata")->required();
    auto* png = cmd->add_option("--png", c->png, "Also write an sRGB PNG preview here");
    cmd->add_option("--exposure", c->exposure,
                    "PNG exposure in stops, with --png (the EXR is never scaled); without it the PNG is exposed from "
                    "the image: the 98th luminance percentile of its pixels above 0 maps to white, in whole thirds "
                    "of a stop")
        ->needs(png);
    cmd->add_flag("--depth-images", c->options.depthImages,
                  "Also write <out>-k<K>.exr for each path length K = 1..max-depth: the Neumann-series terms, which "
                  "add up to the full image");
    inRange(documented(cmd->add_option("--strategy-images", c->options.strategyImages), c->options), kStrategyImagesRange);
    cmd->add_option("--replay", c->replay,
                    "PASS,PIXEL: render that one sample again (PIXEL = y * width + x; for lt that pixel's light paths PIXEL, PIXEL + width * height, ...) with "
                    "the other flags as given, and print each of its contributions (strategy, f/p, MIS weight), NaN or "
                    "infinite ones marked; writes no image (--out is still required). A render that drops NaN/Inf "
                    "samples prints the first ones' PASS,PIXEL");
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
