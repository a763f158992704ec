// The glTF file and the files it names, read through tinygltf (gltf_file.h): which buffer files
// tinygltf may open is decided here, before it parses, and enforced by its file-system callbacks.
#include "geometry/gltf_file.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>

#include "geometry/external_files.h"

namespace tripath::gltf {

namespace {

// Collapses tinygltf's multi-line messages into one line.
std::string oneLine(const std::string& text) {
    std::string out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (line.empty()) continue;
        if (!out.empty()) out += "; ";
        out += line;
    }
    return out;
}

// Quoted for a one-line message: quotes, backslashes and control characters are escaped.
std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (byte < 0x20 || byte == 0x7f) {
            static const char* const kHex = "0123456789abcdef";
            out += "\\x";
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        } else {
            out += c;
        }
    }
    return out + "\"";
}

// The JSON chunk of a GLB file; empty when the header is malformed (tinygltf then says how).
std::string_view glbJsonChunk(const std::vector<char>& bytes) {
    constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON", little-endian
    if (bytes.size() < 20) return {};
    uint32_t length = 0, type = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    std::memcpy(&type, bytes.data() + 16, 4);
    if (type != kJsonChunk || length > bytes.size() - 20) return {};
    return {bytes.data() + 20, length};
}

// The files tinygltf may open: the resolved paths of the buffer files approveBufferFiles let
// through. The callbacks get each URI decoded (the model is loaded with an empty base folder)
// and resolve it against the scene's folder again; everything else, image files included, is
// reported missing.
struct ApprovedFiles {
    std::filesystem::path folder;
    bool allowOutside = false;
    std::set<std::filesystem::path> files;

    // The file `decodedUri` names, or an empty path when it was not approved.
    std::filesystem::path find(const std::string& decodedUri) const {
        const ExternalFile file = resolveExternalFile(folder, decodedUri, allowOutside);
        return file.problem.empty() && files.count(file.path) ? file.path : std::filesystem::path();
    }
};

bool approvedFileExists(const std::string& decodedUri, void* approved) {
    return !static_cast<const ApprovedFiles*>(approved)->find(decodedUri).empty();
}

std::string keepPath(const std::string& path, void*) { return path; }

bool readApprovedFile(std::vector<unsigned char>* out, std::string* err, const std::string& decodedUri,
                      void* approved) {
    const std::filesystem::path path = static_cast<const ApprovedFiles*>(approved)->find(decodedUri);
    if (!path.empty()) {
        std::error_code ec;
        const uintmax_t size = std::filesystem::file_size(path, ec);
        std::ifstream in(path, std::ios::binary);
        if (!ec && in) {
            out->resize(size_t(size));
            if (in.read(reinterpret_cast<char*>(out->data()), std::streamsize(out->size()))) return true;
        }
    }
    *err += "cannot read " + quoted(decodedUri);
    return false;
}

// Textures are not supported: accept every image without decoding it.
bool skipImageDecoding(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                       const unsigned char*, int, void*) {
    return true;
}

std::vector<char> readSceneFile(const Report& report) {
    const std::string& path = report.path();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) report.fail("file not found");
    if (!std::filesystem::is_regular_file(path, ec)) report.fail("not a regular file");
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size > UINT_MAX) report.fail("file is larger than 4 GiB (not supported)");
    std::vector<char> bytes(ec ? 0 : size_t(size));
    std::ifstream in(path, std::ios::binary);
    if (bytes.size() < 4 || !in || !in.read(bytes.data(), std::streamsize(bytes.size())))
        report.fail("cannot read file (empty or unreadable)");
    return bytes;
}

// Checks every external buffer URI before tinygltf opens any file, so that a refusal names the
// buffer; approves the files that pass. JSON that does not parse is left for tinygltf to report.
void approveBufferFiles(std::string_view json, ApprovedFiles& approved, const Report& report) {
    const auto doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
    if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return;
    const auto& buffers = doc["buffers"];
    for (size_t i = 0; i < buffers.size(); ++i) {
        const auto& buffer = buffers[i];
        if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
        const std::string& uri = buffer["uri"].get_ref<const std::string&>();
        if (uri.empty() || tinygltf::IsDataURI(uri)) continue;
        const ExternalFile file = resolveExternalFile(approved.folder, decodeUriPath(uri), approved.allowOutside);
        if (!file.problem.empty()) {
            std::string name = "buffer " + std::to_string(i);
            if (buffer.contains("name") && buffer["name"].is_string())
                name += " " + quoted(buffer["name"].get_ref<const std::string&>());
            report.fail(name + ": uri " + quoted(uri) + " names " + quoted(file.path.string()) + ", " + file.problem);
        }
        approved.files.insert(file.path);
    }
}

// tinygltf's own warnings, minus those about image files: textures are ignored anyway (and a
// missing file only warns for images; a missing buffer is an error).
void forwardLibraryWarnings(const std::string& text, Report& report) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        line = oneLine(line);
        const bool aboutImages = line.find("image") != std::string::npos ||
                                 line.find("Image") != std::string::npos ||
                                 line.rfind("File not found", 0) == 0;
        if (!line.empty() && !aboutImages) report.warnOnce(line);
    }
}

}  // namespace

tinygltf::Model readModel(bool allowExternalFiles, Report& report) {
    const std::string& path = report.path();
    const std::vector<char> bytes = readSceneFile(report);
    const bool binary = std::memcmp(bytes.data(), "glTF", 4) == 0 ||
                        std::filesystem::path(path).extension() == ".glb";
    ApprovedFiles approved;
    approved.allowOutside = allowExternalFiles;
    std::error_code ec;
    approved.folder = std::filesystem::canonical(std::filesystem::absolute(path).parent_path(), ec);
    if (ec) report.fail("cannot resolve the scene's folder (" + ec.message() + ")");
    approveBufferFiles(binary ? glbJsonChunk(bytes) : std::string_view(bytes.data(), bytes.size()), approved,
                       report);

    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&skipImageDecoding, nullptr);
    parser.SetFsCallbacks({&approvedFileExists, &keepPath, &readApprovedFile, nullptr, &approved});
    tinygltf::Model model;
    std::string err, warnings;
    bool ok = false;
    try {
        const auto size = static_cast<unsigned int>(bytes.size());
        ok = binary ? parser.LoadBinaryFromMemory(&model, &err, &warnings,
                                                  reinterpret_cast<const unsigned char*>(bytes.data()), size, "")
                    : parser.LoadASCIIFromString(&model, &err, &warnings, bytes.data(), size, "");
    } catch (const std::exception& e) {
        report.fail(std::string("cannot parse glTF: ") + e.what());
    }
    forwardLibraryWarnings(warnings, report);
    if (!ok) report.fail(err.empty() ? std::string("cannot parse glTF") : oneLine(err));
    return model;
}

}  // namespace tripath::gltf
