// A render's estimate against its budget (memory_check.h).
#include "requests/memory_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "core/available_memory.h"
#include "core/byte_size.h"
#include "core/error.h"
#include "io/gltf_checks.h"

namespace tripath {

namespace {

// How many of the largest parts the message names, and the share of the estimate a part must have
// for its flags to be suggested.
constexpr size_t kPartsNamed = 3;
constexpr double kShareToLower = 0.1;

// "width/height" as `spelling` writes each flag: "--width/--height", "width/height".
std::string spelt(const std::string& flags, Spelling spelling) {
    std::string out;
    std::istringstream pieces(flags);
    for (std::string piece; std::getline(pieces, piece, '/');) out += (out.empty() ? "" : "/") + parameterName(piece.c_str(), spelling);
    return out;
}

// "lower --width/--height or --light-paths": the flags of the parts that weigh, largest part first
// (at least the largest part's that has flags); or, when what no flag lowers exceeds the budget
// alone, that.
std::string remedy(const MemoryEstimate& e, uint64_t budget, Spelling spelling) {
    uint64_t fixed = 0;
    for (const MemoryPart& p : e.parts) fixed += p.lowerWith.empty() ? p.bytes : 0;
    if (fixed > budget) return "the process and its scene alone take " + bytesText(fixed);
    std::vector<std::string> flags;
    for (const MemoryPart& p : e.parts)
        if (flags.empty() || double(p.bytes) >= kShareToLower * double(e.total()))
            for (const std::string& f : p.lowerWith)
                if (std::find(flags.begin(), flags.end(), f) == flags.end()) flags.push_back(f);
    std::string text = "lower " + spelt(flags[0], spelling);
    for (size_t i = 1; i < flags.size(); ++i) text += (i + 1 == flags.size() ? " or " : ", ") + spelt(flags[i], spelling);
    return text;
}

}  // namespace

std::optional<uint64_t> memoryLimit(const RenderRequest& r) {
    return r.memoryLimitGiven ? std::optional(r.memoryLimit) : std::nullopt;
}

uint64_t parseMemoryLimit(const std::string& text, Spelling spelling) {
    const std::optional<uint64_t> bytes = parseByteSize(text);
    if (!bytes || *bytes == 0)
        throw InputError(fmt::format("{} must be a size above 0 such as 8G, 512M or 1.5T (got '{}')",
                                     parameterName("memory-limit", spelling), gltf::excerpt(text)));
    return *bytes;
}

void requireMemory(const MemoryEstimate& estimate, std::optional<uint64_t> limit, Spelling spelling) {
    std::string budget, override;
    uint64_t bytes = 0;
    const std::string flag = parameterName("memory-limit", spelling);
    if (limit) {
        bytes = *limit;
        budget = fmt::format("{} is {}", flag, bytesText(bytes));
        override = "raise " + flag;
    } else {
        const std::optional<AvailableMemory> machine = availableMemory();
        if (!machine) return;
        bytes = machine->bytes;
        budget = fmt::format("{} is available ({})", bytesText(bytes), machine->limitBy);
        override = "give " + flag + " to render anyway";
    }
    if (estimate.total() <= bytes) return;
    std::string parts;
    for (size_t i = 0; i < std::min(kPartsNamed, estimate.parts.size()); ++i)
        parts += fmt::format("{}{} {}", i ? ", " : "", estimate.parts[i].name, bytesText(estimate.parts[i].bytes));
    if (estimate.parts.size() > kPartsNamed) parts += ", ...";
    throw InputError(fmt::format("the render needs an estimated {} ({}) but {}: {}, or {}", bytesText(estimate.total()),
                                 parts, budget, remedy(estimate, bytes, spelling), override));
}

}  // namespace tripath
