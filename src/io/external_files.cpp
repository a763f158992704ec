// The policy for files named by glTF buffer URIs (see external_files.h for the rules and why).
#include "io/external_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <system_error>

namespace tripath {

namespace fs = std::filesystem;

namespace {

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// True when `path` is `folder` or lies below it (both absolute and normalised).
bool isInside(const fs::path& path, const fs::path& folder) {
    const fs::path relative = path.lexically_relative(folder);
    return !relative.empty() && *relative.begin() != "..";
}

const char* const kOnlyInside =
    "only files in the scene's folder and its subfolders are read; --allow-external-files lifts this";

}  // namespace

std::string uriScheme(const std::string& uri) {
    // A letter, then letters, digits, '+', '-' or '.', then ':'.
    const auto isSchemeChar = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
    };
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return "";
    const size_t colon = uri.find(':');
    if (colon == std::string::npos || !std::all_of(uri.begin(), uri.begin() + long(colon), isSchemeChar)) return "";
    return uri.substr(0, colon);
}

std::string decodeUriPath(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && i + 2 < uri.size() && hexValue(uri[i + 1]) >= 0 && hexValue(uri[i + 2]) >= 0) {
            out += char(hexValue(uri[i + 1]) * 16 + hexValue(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

std::string encodeUriPath(const std::string& path) {
    std::string out;
    for (const char c : path) {
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/')
            out += c;
        else
            out += fmt::format("%{:02X}", static_cast<unsigned char>(c));
    }
    return out;
}

ExternalFile resolveExternalFile(const fs::path& folder, const std::string& decoded, bool allowOutside) {
    const fs::path given(decoded);
    // The system would see the path cut at the NUL, not the one checked here.
    if (decoded.find('\0') != std::string::npos) return {given, "which contains a NUL character"};
    if (given.is_absolute() && !allowOutside)
        return {given.lexically_normal(), std::string("an absolute path (") + kOnlyInside + ")"};
    std::error_code ec;
    const fs::path path = fs::weakly_canonical(folder / given, ec);
    if (ec) return {(folder / given).lexically_normal(), "which cannot be resolved (" + ec.message() + ")"};
    if (!allowOutside && !isInside(path, folder))
        return {path, "outside the scene's folder " + folder.string() + " (" + kOnlyInside + ")"};
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) return {path, "which does not exist"};
    if (ec) return {path, "which cannot be read (" + ec.message() + ")"};
    if (status.type() == fs::file_type::directory) return {path, "which is a directory, not a file"};
    if (status.type() != fs::file_type::regular) return {path, "which is not a regular file"};
    return {path, ""};
}

}  // namespace tripath
