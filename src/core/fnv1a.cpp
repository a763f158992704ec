#include "core/fnv1a.h"

#include <fmt/format.h>

namespace tripath {

std::string hashText(uint64_t hash) { return fmt::format("{:016x}", hash); }

}  // namespace tripath
