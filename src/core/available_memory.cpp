// What the machine can still give this process (available_memory.h).
#include "core/available_memory.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/number_text.h"

namespace tripath {

namespace fs = std::filesystem;

namespace {

// A group limit this large or larger means none: version 1 writes 2^63 rounded down to a page.
constexpr uint64_t kNoLimit = uint64_t(1) << 62;

std::optional<std::string> readText(const fs::path& file) {
    std::ifstream in(file);
    if (!in) return std::nullopt;
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The whole number a one-number file holds ("max" and anything else: nullopt).
std::optional<uint64_t> readNumber(const fs::path& file) {
    std::optional<std::string> text = readText(file);
    if (!text) return std::nullopt;
    while (!text->empty() && (text->back() == '\n' || text->back() == ' ')) text->pop_back();
    return parseWholeNumber(*text, UINT64_MAX);
}

// The number after "key" on its line of a "key value [unit]" file (meminfo, status, memory.stat).
std::optional<uint64_t> field(const std::string& text, std::string_view key) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        if (!line.starts_with(key) || line.size() == key.size() || (line[key.size()] != ' ' && line[key.size()] != '\t'))
            continue;
        std::istringstream rest(line.substr(key.size()));
        std::string number;
        rest >> number;
        return parseWholeNumber(number, UINT64_MAX);
    }
    return std::nullopt;
}

// A group's files: its limit, its usage, and the memory.stat key of its droppable page cache.
struct GroupFiles {
    fs::path mount;  // where the hierarchy is mounted
    std::string path;  // the process's group in it, from /proc/self/cgroup
    const char *limit, *usage, *inactive;
};

// The groups /proc/self/cgroup puts this process in that account for memory: version 2's single
// hierarchy ("0::/path") and version 1's memory controller ("N:memory:/path", or with others
// "N:cpu,memory:/path").
std::vector<GroupFiles> memoryGroups(const fs::path& root) {
    std::vector<GroupFiles> groups;
    const std::optional<std::string> text = readText(root / "proc/self/cgroup");
    if (!text) return groups;
    std::istringstream lines(*text);
    for (std::string line; std::getline(lines, line);) {
        const size_t first = line.find(':'), second = line.find(':', first + 1);
        if (first == std::string::npos || second == std::string::npos) continue;
        std::istringstream controllers(line.substr(first + 1, second - first - 1));
        bool memory = false;
        for (std::string name; std::getline(controllers, name, ',');) memory = memory || name == "memory";
        const std::string path = line.substr(second + 1);
        if (line.substr(0, first) == "0" && second == first + 1)
            groups.push_back({root / "sys/fs/cgroup", path, "memory.max", "memory.current", "inactive_file"});
        else if (memory)
            groups.push_back({root / "sys/fs/cgroup/memory", path, "memory.limit_in_bytes", "memory.usage_in_bytes",
                              "total_inactive_file"});
    }
    return groups;
}

struct Headroom {
    uint64_t bytes;
    std::string limitBy;
};

// The smallest headroom of the group's directory and each of its parents up to the mount (a
// parent's limit binds its children too). A process in a group namespace sees its own group at the
// mount's root, while /proc/self/cgroup may still name the group's path outside it: a path that
// does not exist under the mount is read from the mount's root.
std::optional<Headroom> groupHeadroom(const GroupFiles& g) {
    const fs::path inside = fs::path(g.path).relative_path();
    fs::path dir = g.mount / inside;
    std::error_code ec;
    if (inside.empty() || !fs::is_directory(dir, ec)) dir = g.mount;
    std::optional<Headroom> least;
    for (;;) {
        const std::optional<uint64_t> limit = readNumber(dir / g.limit), usage = readNumber(dir / g.usage);
        if (limit && usage && *limit < kNoLimit) {
            const std::optional<std::string> stat = readText(dir / "memory.stat");
            const uint64_t droppable = stat ? field(*stat, g.inactive).value_or(0) : 0;
            const uint64_t used = *usage - std::min(*usage, droppable);
            const uint64_t room = *limit - std::min(*limit, used);
            if (!least || room < least->bytes) least = Headroom{room, std::string("cgroup ") + g.limit};
        }
        if (dir == g.mount || dir.parent_path() == dir) break;
        dir = dir.parent_path();
    }
    return least;
}

}  // namespace

std::optional<AvailableMemory> availableMemory(const fs::path& root) {
    const std::optional<std::string> meminfo = readText(root / "proc/meminfo"), status = readText(root / "proc/self/status");
    if (!meminfo || !status) return std::nullopt;
    const std::optional<uint64_t> availableKiB = field(*meminfo, "MemAvailable:"), residentKiB = field(*status, "VmRSS:");
    if (!availableKiB || !residentKiB) return std::nullopt;
    Headroom headroom{*availableKiB * 1024, "MemAvailable"};
    for (const GroupFiles& g : memoryGroups(root))
        if (const std::optional<Headroom> room = groupHeadroom(g); room && room->bytes < headroom.bytes) headroom = *room;
    return AvailableMemory{*residentKiB * 1024 + headroom.bytes, headroom.limitBy};
}

}  // namespace tripath
