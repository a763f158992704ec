// How much memory this process can count on before it allocates a render's film and light paths
// (docs/design.md §5): what it holds already plus what the machine can still give it. That is
// Linux's MemAvailable (/proc/meminfo: free memory and the caches the kernel can drop, without
// swapping) or, when the process runs in a control group with a memory limit (a container, a
// batch job's allocation), that limit less what the group uses, whichever is smaller. A group
// counts its page cache as used; the part the kernel drops first (inactive_file) is taken as free,
// as container runtimes do. Every group from the process's own up to the root is read, version 2
// (memory.max, memory.current) or version 1 (memory.limit_in_bytes, memory.usage_in_bytes).
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace tripath {

struct AvailableMemory {
    uint64_t bytes = 0;   // resident now (VmRSS) + the smaller headroom
    std::string limitBy;  // what set the headroom: "MemAvailable", "cgroup memory.max" or "cgroup memory.limit_in_bytes"
};

// Read from `root`'s /proc and /sys/fs/cgroup (root is "/" but for tests, which build a tree of
// such files); nullopt where /proc/meminfo or /proc/self/status cannot be read (not Linux).
std::optional<AvailableMemory> availableMemory(const std::filesystem::path& root = "/");

}  // namespace tripath
