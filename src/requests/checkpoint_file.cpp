#include "requests/checkpoint_file.h"

#include <fmt/format.h>

#include <bit>
#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fnv1a.h"
#include "core/number_text.h"
#include "requests/scene_identity.h"

namespace tripath {

namespace {

constexpr const char* kFormat = "tripath-checkpoint";
constexpr int kVersion = 3;
static_assert(std::endian::native == std::endian::little, "checkpoints store the totals as little-endian words");

// The most seconds a checkpoint may give: the command line (apps/checkpoint.h) sends them to the
// other ranks in microseconds, as a 64-bit integer. 1e9 s is 31 years.
constexpr double kMaxSeconds = 1e9;

// The words of a film's exact totals: three per value, three values per pixel of each image.
size_t wordCount(int width, int height, const FilmLayers& layers) {
    return Film::images(layers) * 9 * size_t(width) * size_t(height);
}
size_t wordCount(const Film& film) { return wordCount(film.width(), film.height(), film.layers()); }

}  // namespace

void writeCheckpoint(const std::string& path, const Metadata& settings, const RenderResult& r) {
    std::string header;
    for (const auto& [key, value] : settings) header += key + "=" + value + "\n";
    header += fmt::format("passes={}\nnext-pass={}\nseconds={:.6f}\ndropped-samples={}\nguarded-weights={}\n"
                          "values={}\nchain-run={}\nstate-bytes={}\n",
                          r.passes, r.nextPass, r.seconds, r.droppedSamples, r.guardedWeights, wordCount(r.film),
                          r.metropolis.run, r.methodState.size());
    Fnv1a sum;
    sum.add(header);
    for (const ExactSums* t : r.film.totals()) sum.add(t->words().data(), t->words().size_bytes());
    sum.add(r.methodState.data(), r.methodState.size());
    writeFileAtomically(path, [&](std::ostream& f) {
        f << kFormat << " " << kVersion << "\n" << header << "checksum=" << hashText(sum.value()) << "\n\n";
        for (const ExactSums* t : r.film.totals())
            f.write(reinterpret_cast<const char*>(t->words().data()), std::streamsize(t->words().size_bytes()));
        f.write(r.methodState.data(), std::streamsize(r.methodState.size()));
    });
}

std::optional<RenderResult> readCheckpoint(const std::string& path, const Metadata& settings, int width, int height,
                                           const FilmLayers& layers) {
    auto bad = [&](const std::string& why) { return InputError(fmt::format("checkpoint '{}': {}", path, why)); };
    std::error_code ec;
    const std::filesystem::file_type type = std::filesystem::status(path, ec).type();
    if (type == std::filesystem::file_type::not_found) return std::nullopt;
    if (ec) throw bad("cannot read it (" + ec.message() + ")");
    // A FIFO would block until a writer comes, a device never end.
    if (type != std::filesystem::file_type::regular) throw bad("not a regular file");
    std::ifstream f(path, std::ios::binary);
    if (!f) throw bad("cannot open it");
    std::string line;
    const std::string format = std::string(kFormat) + " ";
    if (!std::getline(f, line) || !line.starts_with(format)) throw bad("not a tripath checkpoint");
    if (line != format + std::to_string(kVersion))
        throw bad(fmt::format("written in format '{}', this tripath reads format {} (remove it to start afresh)",
                              clipped(line.substr(format.size())), kVersion));
    // The header's lines, and the checksum of all but the checksum's own.
    std::map<std::string, std::string> header;
    Fnv1a sum;
    while (std::getline(f, line) && !line.empty()) {
        const size_t eq = line.find('=');
        if (eq == std::string::npos) throw bad("malformed header line '" + clipped(line) + "'");
        header[line.substr(0, eq)] = line.substr(eq + 1);
        if (line.substr(0, eq) != "checksum") sum.add(line + "\n");
    }
    if (!f) throw bad("cut short");
    for (const auto& [key, value] : settings) {
        const auto it = header.find(key);
        if (key == kSceneFilesKey && it != header.end()) {
            const std::string difference = sceneFilesDifference(it->second, value);
            if (!difference.empty())
                throw bad("it was made from other scene files: " + difference + " (remove it to start afresh)");
            continue;
        }
        if (it == header.end() || it->second != value)
            throw bad(fmt::format("it was made with {}={}, this run has {} (remove it to start afresh)", key,
                                  it == header.end() ? "(nothing)" : clipped(it->second), value));
    }
    auto text = [&](const char* key) {
        const auto it = header.find(key);
        if (it == header.end()) throw bad(std::string("no ") + key);
        return it->second;
    };
    auto number = [&](const char* key, uint64_t max) {
        const std::string value = text(key);
        const auto parsed = parseWholeNumber(value, max);
        if (!parsed) throw bad(fmt::format("{} is '{}', not a whole number from 0 to {}", key, clipped(value), max));
        return *parsed;
    };
    RenderResult r{Film(width, height, layers)};
    r.passes = int(number("passes", INT_MAX));
    r.nextPass = number("next-pass", kMaxFirstPass);
    if (uint64_t(r.passes) > r.nextPass)
        throw bad(fmt::format("it gives {} passes, more than its next-pass {} leaves room for", r.passes, r.nextPass));
    const std::string seconds = text("seconds");
    const auto parsedSeconds = parseNonNegative(seconds, kMaxSeconds);
    if (!parsedSeconds)
        throw bad(fmt::format("seconds is '{}', not a number from 0 to {:g}", clipped(seconds), kMaxSeconds));
    r.seconds = *parsedSeconds;
    r.droppedSamples = number("dropped-samples", UINT64_MAX);
    r.guardedWeights = number("guarded-weights", UINT64_MAX);
    r.metropolis.run = number("chain-run", UINT64_MAX);
    const size_t words = wordCount(width, height, layers);
    if (number("values", UINT64_MAX) != words) throw bad("its film has another size or other layers");
    // The method's state is what follows the totals: its size is checked against the file's
    // before anything is allocated for it.
    const uint64_t stateBytes = number("state-bytes", UINT64_MAX);
    const uint64_t fileSize = std::filesystem::file_size(path, ec);
    if (ec) throw bad("cannot read it (" + ec.message() + ")");
    const uint64_t totalsEnd = uint64_t(std::streamoff(f.tellg())) + words * sizeof(uint64_t);
    if (fileSize < totalsEnd) throw bad("cut short");
    if (fileSize - totalsEnd != stateBytes)
        throw bad(fmt::format("its header gives state-bytes={}, but {} bytes follow its totals", stateBytes,
                              fileSize - totalsEnd));
    for (ExactSums* t : r.film.totals()) {
        if (!f.read(reinterpret_cast<char*>(t->words().data()), std::streamsize(t->words().size_bytes())))
            throw bad("cut short");
        sum.add(t->words().data(), t->words().size_bytes());
    }
    r.methodState.resize(stateBytes);
    if (!f.read(r.methodState.data(), std::streamsize(stateBytes))) throw bad("cut short");
    sum.add(r.methodState.data(), stateBytes);
    if (text("checksum") != hashText(sum.value()))
        throw bad("its contents do not match its checksum: the file is damaged (remove it to start afresh)");
    return r;
}

}  // namespace tripath
