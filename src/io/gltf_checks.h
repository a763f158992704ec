// What the pieces of the glTF loader share to check what they read and to say what is wrong: a
// failure is one InputError line that starts with the file's path, a warning reaches the sink
// once per message whichever piece finds it. A header of the io library's own (the
// loader's interface is gltf_loader.h).
#pragma once
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec.h"
#include "core/warnings.h"

namespace tripath::gltf {

// Failures and warnings about one glTF file.
class Report {
public:
    Report(std::string path, WarningSink warn) : path_(std::move(path)), warn_(std::move(warn)) {}
    const std::string& path() const { return path_; }

    // Throws InputError("<path>: <what>").
    [[noreturn]] void fail(const std::string& what) const { throw InputError(path_ + ": " + what); }
    // Passes "<path>: <what>" to the sink, the first time only.
    void warnOnce(const std::string& what) {
        if (warned_.insert(what).second && warn_) warn_(path_ + ": " + what);
    }

private:
    std::string path_;
    WarningSink warn_;
    std::set<std::string> warned_;
};

// Shortest readable form of a number for messages ("4", "0.25", "1e+39").
std::string formatNumber(double value);

// Text from the file, as a message quotes it: at most maxBytes of it (cut at a character
// boundary), the rest replaced by "... (N bytes)", so that a name or URI of any length (a
// buffer's whole base64 payload) leaves the message one readable line.
constexpr size_t kExcerptLength = 60;
std::string excerpt(const std::string& text, size_t maxBytes = kExcerptLength);

// excerpt(text, maxBytes) in double quotes, its quotes, backslashes and control characters escaped.
std::string quoted(const std::string& text, size_t maxBytes = kExcerptLength);

// True when every value stays finite as a float, the precision the scene keeps.
bool allFinite(const std::vector<double>& values);

// The three components of a colour or vector, or `fallback` when the file gives none; fails when
// there are fewer than three or they are not finite.
Vec3 finiteVec3(const std::vector<double>& values, Vec3 fallback, const std::string& what, const Report& report);

// True for the extensions whose content the loader reads; the others are ignored with a warning.
bool isHandledExtension(const std::string& name);

}  // namespace tripath::gltf
