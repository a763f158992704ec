// The memory check of a render (docs/design.md §5): its estimate (integrators/memory_estimate.h)
// against its budget, before the film and the light paths are allocated. The budget is the
// request's memory limit (--memory-limit, Python's memory_limit) when given, else what the
// machine can give the process when the check runs (core/available_memory.h). A limit above what
// the machine has is how a user renders anyway (with swap, or memory about to be freed): there is
// no other override, so whoever overrides says how much they count on.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "integrators/memory_estimate.h"
#include "requests/render_request.h"

namespace tripath {

// The request's memory limit when given; nullopt: what the machine has.
std::optional<uint64_t> memoryLimit(const RenderRequest& r);

// A memory limit as given ("8G", "512M", "1.5T": core/byte_size.h), in bytes; InputError naming
// the parameter as `spelling` writes it for anything else, and for 0.
uint64_t parseMemoryLimit(const std::string& text, Spelling spelling);

// Throws InputError when `estimate` exceeds `limit` (nullopt: what the machine has; nothing is
// checked where that cannot be read), in one line: the estimate and its largest parts, the budget
// and where it comes from, and the flags that shrink those parts, spelt as `spelling` writes them.
void requireMemory(const MemoryEstimate& estimate, std::optional<uint64_t> limit, Spelling spelling);

}  // namespace tripath
