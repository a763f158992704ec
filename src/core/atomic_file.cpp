#include "core/atomic_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>

#include <atomic>
#include <charconv>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace tripath {

namespace fs = std::filesystem;

namespace {

// Unique among concurrent writers: the pid separates processes, the counter threads and calls.
std::string uniqueSuffix() {
    static std::atomic<unsigned long long> counter{0};
    return fmt::format("{}-{}", static_cast<long>(::getpid()), counter.fetch_add(1));
}

// Removes the temporaries of `path` ("<name>.tmp-<pid>-<n><ext>" beside it) whose process is gone:
// what a writer killed mid-write (SIGKILL, a crash) left. A temporary whose pid runs (this
// process, another writer, or a process that reused the pid) is left alone.
void removeLeftovers(const fs::path& path) {
    const std::string prefix = path.filename().string() + ".tmp-";
    std::error_code ec;  // a folder that cannot be listed ends the search; a file that cannot be removed stays
    const fs::path dir = path.parent_path();
    for (fs::directory_iterator it(dir.empty() ? "." : dir, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        const fs::path& entry = it->path();
        const std::string name = entry.filename().string();
        if (!name.starts_with(prefix)) continue;
        long pid = 0;
        const char *begin = name.data() + prefix.size(), *end = name.data() + name.size();
        const auto [stop, parseError] = std::from_chars(begin, end, pid);
        if (parseError != std::errc{} || stop == end || *stop != '-' || pid <= 0) continue;
        std::error_code ignored;
        if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove(entry, ignored);
    }
}

}  // namespace

void checkTarget(const std::string& path) {
    if (path.empty()) throw InputError("cannot write: empty output path");
    std::error_code ec;
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty()) dir = ".";
    if (!fs::exists(dir, ec))
        throw InputError(fmt::format("cannot write '{}': directory '{}' does not exist", path, dir.string()));
    if (!fs::is_directory(dir, ec))
        throw InputError(fmt::format("cannot write '{}': '{}' is not a directory", path, dir.string()));
    if (fs::is_directory(path, ec)) throw InputError(fmt::format("cannot write '{}': it is a directory", path));
    // Renaming over a symlink would replace the link, not what it names, and over a device or a
    // FIFO the special file itself: both are refused, as the readers refuse them.
    const fs::file_status status = fs::symlink_status(path, ec);
    if (!ec && fs::exists(status) && !fs::is_regular_file(status))
        throw InputError(fmt::format("cannot write '{}': it is {}, which tripath does not replace", path,
                                     fs::is_symlink(status) ? "a symbolic link" : "a device, FIFO or socket"));
}

void checkWritable(const std::string& path) {
    checkTarget(path);
    // Permission bits alone do not tell (ACLs, read-only mounts, quotas), so actually create a
    // file. O_EXCL: never clobber someone else's file.
    const std::string probe = fmt::format("{}.probe-{}", path, uniqueSuffix());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        const int err = errno;
        fs::path dir = fs::path(path).parent_path();
        throw InputError(fmt::format("cannot write '{}': directory '{}' is not writable: {}", path,
                                     (dir.empty() ? fs::path(".") : dir).string(),
                                     std::error_code(err, std::generic_category()).message()));
    }
    ::close(fd);
    ::unlink(probe.c_str());
}

void replaceAtomically(const std::string& path, const std::string& ext, const std::function<void(const std::string&)>& write) {
    checkTarget(path);
    const std::string tmp = fmt::format("{}.tmp-{}{}", path, uniqueSuffix(), ext);
    try {
        write(tmp);
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (ec) throw InputError(fmt::format("cannot write '{}': rename failed: {}", path, ec.message()));
        removeLeftovers(path);
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
    replaceAtomically(path, ".part", [&](const std::string& tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw InputError(fmt::format("cannot write '{}': cannot create a file in its folder", path));
        write(out);
        out.close();
        if (!out) throw InputError(fmt::format("cannot write '{}': write failed (disk full?)", path));
    });
}

}  // namespace tripath
