// Which files a glTF buffer URI may name, and how the URI becomes a path. A scene file is input
// from anywhere, so by default it may only read files in its own folder and its subfolders: never
// a directory, device or fifo (reading one either fails late with a giant allocation or blocks),
// and never a file elsewhere on the machine (/etc/…, /proc/…) passed off as geometry.
#pragma once
#include <filesystem>
#include <string>

namespace tripath {

// The scheme of a URI, as RFC 3986 spells it: "http" of "http://host/a.bin", "file" of
// "file:///a.bin"; empty when the URI has none (a relative reference such as "a.bin" or "a/b:c.bin").
std::string uriScheme(const std::string& uri);

// Decodes a URI's %XX escapes and turns '+' into a space, as tinygltf does before it looks a file
// up. A '%' not followed by two hex digits stays as it is.
std::string decodeUriPath(const std::string& uri);

// The URI reference of a relative path: every byte but an unreserved one (letters, digits, '-',
// '.', '_', '~') and '/' as a %XX escape, so decodeUriPath gives the path back.
std::string encodeUriPath(const std::string& path);

// Where a decoded URI points, and whether it may be read.
struct ExternalFile {
    std::filesystem::path path;  // absolute and with symlinks resolved (as given when refused for being absolute)
    std::string problem;         // empty when the file may be read; else the reason, a phrase such as
                                 // "which is a directory, not a file"
};

// Resolves a decoded URI against `folder` (the scene's folder: absolute, symlinks resolved).
// Refused: a path with a NUL character, anything that is not a regular file once symlinks are
// followed, and, unless allowOutside, an absolute path or one that ends up outside `folder`
// (through `..` or a symlink).
ExternalFile resolveExternalFile(const std::filesystem::path& folder, const std::string& decoded,
                                 bool allowOutside);

}  // namespace tripath
