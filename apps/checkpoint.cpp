#include "checkpoint.h"

#include <fmt/format.h>

#include <array>
#include <bit>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "geometry/embree_isa.h"
#include "core/error.h"
#include "processes.h"

namespace tripath::app {

namespace {

constexpr const char* kMagic = "tripath-checkpoint 1";
static_assert(std::endian::native == std::endian::little, "checkpoints store the totals as little-endian words");

size_t wordCount(const Film& film) {
    size_t n = 0;
    for (const ExactSums* t : film.totals()) n += t->words().size();
    return n;
}

}  // namespace

std::string checkpointPath(const std::string& out) { return out + ".checkpoint"; }

void writeCheckpoint(const std::string& path, const Metadata& settings, const RenderResult& r) {
    writeFileAtomically(path, [&](std::ostream& f) {
        f << kMagic << "\n";
        for (const auto& [key, value] : settings) f << key << "=" << value << "\n";
        f << "passes=" << r.passes << "\nnext-pass=" << r.nextPass << "\nseconds=" << fmt::format("{:.6f}", r.seconds)
          << "\ndropped-samples=" << r.droppedSamples << "\nguarded-weights=" << r.guardedWeights
          << "\nvalues=" << wordCount(r.film) << "\nchain-run=" << r.metropolis.run
          << "\nchain-bytes=" << r.metropolis.chainStates.size() << "\n\n";
        for (const ExactSums* t : r.film.totals())
            f.write(reinterpret_cast<const char*>(t->words().data()), std::streamsize(t->words().size_bytes()));
        f.write(r.metropolis.chainStates.data(), std::streamsize(r.metropolis.chainStates.size()));
    });
}

std::optional<RenderResult> readCheckpoint(const std::string& path, const Metadata& settings, const Film& shape) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return std::nullopt;
    auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint '{}': {}", path, why)); };
    std::string line;
    if (!std::getline(f, line) || line != kMagic) throw bad("not a tripath checkpoint");
    std::map<std::string, std::string> header;
    while (std::getline(f, line) && !line.empty()) {
        const size_t eq = line.find('=');
        if (eq == std::string::npos) throw bad("malformed header line '" + line + "'");
        header[line.substr(0, eq)] = line.substr(eq + 1);
    }
    for (const auto& [key, value] : settings) {
        const auto it = header.find(key);
        if (it == header.end() || it->second != value)
            throw bad(fmt::format("it was made with {}={}, this run has {} (remove it to start afresh)", key,
                                  it == header.end() ? "(nothing)" : it->second, value));
    }
    auto number = [&](const char* key) {
        const auto it = header.find(key);
        if (it == header.end()) throw bad(std::string("no ") + key);
        return it->second;
    };
    RenderResult r{shape};
    r.passes = std::atoi(number("passes").c_str());
    r.nextPass = std::strtoull(number("next-pass").c_str(), nullptr, 10);
    r.seconds = std::strtod(number("seconds").c_str(), nullptr);
    r.droppedSamples = std::strtoull(number("dropped-samples").c_str(), nullptr, 10);
    r.guardedWeights = std::strtoull(number("guarded-weights").c_str(), nullptr, 10);
    if (std::strtoull(number("values").c_str(), nullptr, 10) != wordCount(shape))
        throw bad("its film has another size or other layers");
    for (ExactSums* t : r.film.totals())
        if (!f.read(reinterpret_cast<char*>(t->words().data()), std::streamsize(t->words().size_bytes())))
            throw bad("cut short");
    auto optional = [&](const char* key) { return header.contains(key) ? std::strtoull(header[key].c_str(), nullptr, 10) : 0; };
    r.metropolis.run = optional("chain-run");
    r.metropolis.chainStates.resize(optional("chain-bytes"));
    if (!f.read(r.metropolis.chainStates.data(), std::streamsize(r.metropolis.chainStates.size()))) throw bad("cut short");
    if (f.peek() != std::char_traits<char>::eof()) throw bad("longer than its header says");
    return r;
}

Metadata checkpointSettings(const RenderOptions& o, const Scene& scene, const Integrator& integrator,
                            const FilmLayers& layers) {
    Metadata m = convergenceSettings(o, integrator.name());
    const Metadata more{{"tripath:width", std::to_string(o.width)},
                        {"tripath:height", std::to_string(o.height)},
                        {"tripath:seed", std::to_string(o.seed)},
                        {"tripath:streams", streamsName(o.domain)},
                        {"tripath:embree", embreeDescription()},
                        {"tripath:depth-images", std::to_string(layers.depthImages)},
                        {"tripath:strategy-images", std::to_string(layers.strategyLength)}};
    m.insert(m.end(), more.begin(), more.end());
    const Metadata light = lightPhaseMetadata(o, scene, integrator);
    m.insert(m.end(), light.begin(), light.end());
    return m;
}

RenderResult renderResumable(const Scene& scene, const Integrator& integrator, RenderSettings rs,
                             const RenderOptions& o, const Resumable& how) {
    const std::string path = checkpointPath(how.out);
    FilmLayers layers = rs.layers;
    layers.strategies = integrator.strategies();
    const Film shape(o.width, o.height, layers);
    // Rank 0 reads the checkpoint (the others may not see its folder) and tells them its counts.
    std::optional<RenderResult> old;
    together([&] {
        if (isRankZero()) old = readCheckpoint(path, how.settings, shape);
    });
    std::array<uint64_t, 5> counts{old ? 1u : 0u, old ? uint64_t(old->passes) : 0, old ? old->nextPass : 0,
                                   old ? uint64_t(old->seconds * 1e6) : 0, old ? old->metropolis.run : 0};
    team().max(counts);
    if (counts[0] && !old) {
        old = RenderResult{shape, int(counts[1]), counts[2], counts[3] / 1e6};
        old->metropolis.run = counts[4];  // mlt's chain states travel from rank 0 inside the render
    }
    bool finished = false;  // the checkpoint already holds the whole budget
    if (old) {
        std::cerr << fmt::format("continuing from {}: {} spp, {:.1f} s\n", path, old->passes, old->seconds);
        if (how.budgetIsTotal) {
            finished = (rs.spp > 0 && old->passes >= rs.spp) || (rs.seconds > 0 && old->seconds >= rs.seconds);
            if (rs.spp > 0) rs.spp -= old->passes;
            if (rs.seconds > 0) rs.seconds -= old->seconds;
        }
        rs.resume = &*old;
    }
    const bool checkpointing = o.checkpointSeconds > 0;
    if (checkpointing) {
        rs.checkpointSeconds = o.checkpointSeconds;
        rs.onCheckpoint = [&](const RenderResult& sofar) {
            how.writeImage(sofar);
            writeCheckpoint(path, how.settings, sofar);
        };
    }
    RenderResult r = finished ? std::move(*old) : render(scene, integrator, rs);
    if (isRankZero()) {
        const bool interrupted = rs.stop && rs.stop->load();
        std::error_code ignored;
        if ((checkpointing && interrupted) || (how.keepState && (checkpointing || old)))
            writeCheckpoint(path, how.settings, r);
        else if (old || checkpointing)
            std::filesystem::remove(path, ignored);
    }
    return r;
}

}  // namespace tripath::app
