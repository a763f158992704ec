// The glTF file and the files it names, read through tinygltf (gltf_file.h): which buffer files
// tinygltf may open is decided here, before it parses, and enforced by its file-system callbacks.
#include "io/gltf_file.h"

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

#include "core/fnv1a.h"
#include "io/external_files.h"
#include "io/gltf_document.h"

namespace tripath::gltf {

namespace {

// tinygltf's text as one line, each word of it at most an excerpt and the whole at most
// kLibraryTextLength bytes: its messages quote the file (a buffer's uri with its whole base64
// payload, for one).
constexpr size_t kLibraryTextLength = 160;
std::string libraryText(const std::string& text) {
    std::string out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        std::string shortened;
        for (std::string word; words >> word;) {
            if (!shortened.empty()) shortened += ' ';
            shortened += excerpt(word);
        }
        if (shortened.empty()) continue;
        if (!out.empty()) out += "; ";
        out += shortened;
    }
    return excerpt(out, kLibraryTextLength);
}

// The files tinygltf may open: the resolved paths of the buffer files approveBufferFiles let
// through. The callbacks get each URI decoded (the model is loaded with an empty base folder)
// and resolve it against the scene's folder again; everything else, image files included, is
// reported missing. Each file read is added to `read`.
struct ApprovedFiles {
    std::filesystem::path folder;
    bool allowOutside = false;
    std::set<std::filesystem::path> files;
    std::vector<SourceFile>* read = nullptr;

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
                      void* approvedFiles) {
    const auto* approved = static_cast<const ApprovedFiles*>(approvedFiles);
    const std::filesystem::path path = approved->find(decodedUri);
    if (!path.empty()) {
        std::error_code ec;
        const uintmax_t size = std::filesystem::file_size(path, ec);
        std::ifstream in(path, std::ios::binary);
        if (!ec && in) {
            out->resize(size_t(size));
            if (in.read(reinterpret_cast<char*>(out->data()), std::streamsize(out->size()))) {
                Fnv1a hash;
                hash.add(out->data(), out->size());
                approved->read->push_back({decodedUri, hash.value()});
                return true;
            }
        }
    }
    *err += "cannot read " + quoted(decodedUri);
    return false;
}

// Images are decoded by gltf_textures.cpp, for the textures materials use: tinygltf decodes none.
// It keeps no data: URI, though, so the bytes it decoded from one are kept as they are, in
// Image::image (a bufferView image is read from its buffer, a file from the disk, there).
bool keepDataUriImages(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                       const unsigned char* bytes, int size, void*) {
    if (image->bufferView < 0 && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

std::vector<char> readSceneFile(const Report& report) {
    const std::string& path = report.path();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) report.fail("file not found");
    if (!std::filesystem::is_regular_file(path, ec)) report.fail("not a regular file");
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) report.fail("cannot read the file (" + ec.message() + ")");
    if (size > UINT_MAX) report.fail("file is larger than 4 GiB (not supported)");
    if (size == 0) report.fail("the file is empty");
    std::vector<char> bytes(static_cast<size_t>(size));
    std::ifstream in(path, std::ios::binary);
    if (!in || !in.read(bytes.data(), std::streamsize(bytes.size()))) report.fail("cannot read the file");
    return bytes;
}

// "buffer 3" or "buffer 3 \"name\"", as the messages about a buffer begin.
std::string bufferName(const nlohmann::json& buffer, size_t index) {
    std::string name = "buffer " + std::to_string(index);
    if (buffer.contains("name") && buffer["name"].is_string()) name += ' ' + quoted(buffer["name"].get<std::string>());
    return name;
}

// tinygltf refuses an embedded buffer whose byteLength is not its size by quoting the whole
// base64 payload; this says so in numbers. The payload is decoded as tinygltf decodes it.
void checkDataUri(const nlohmann::json& buffer, const std::string& uri, const std::string& name, const Report& report) {
    std::vector<unsigned char> data;
    std::string mimeType;
    if (!tinygltf::DecodeDataURI(&data, mimeType, uri, 0, false))
        report.fail(name + ": its data: URI holds no base64 data");
    if (!buffer.contains("byteLength") || !buffer["byteLength"].is_number()) return;  // tinygltf says so
    const double byteLength = buffer["byteLength"].get<double>();
    if (byteLength != double(data.size()))
        report.fail(name + ": byteLength is " + formatNumber(byteLength) + ", but its data: URI holds " +
                    std::to_string(data.size()) + " bytes");
}

// Checks every buffer URI before tinygltf opens any file, so that a refusal names the buffer:
// data: URIs hold their byteLength, nothing else has a URI scheme (http:, file:, ... would be
// taken as a file's name), and the files named pass resolveExternalFile; approves those files.
void approveBufferFiles(const nlohmann::json& doc, ApprovedFiles& approved, const Report& report) {
    if (!doc.contains("buffers") || !doc["buffers"].is_array()) return;
    const auto& buffers = doc["buffers"];
    for (size_t i = 0; i < buffers.size(); ++i) {
        const auto& buffer = buffers[i];
        if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
        const std::string& uri = buffer["uri"].get_ref<const std::string&>();
        if (uri.empty()) continue;
        const std::string name = bufferName(buffer, i);
        if (tinygltf::IsDataURI(uri)) {
            checkDataUri(buffer, uri, name, report);
            continue;
        }
        const std::string scheme = uriScheme(uri);
        if (scheme == "data")
            report.fail(name + ": uri " + quoted(uri) + " is a data: URI that is not base64 " +
                        "application/octet-stream or application/gltf-buffer (not supported)");
        if (!scheme.empty())
            report.fail(name + ": uri " + quoted(uri) + ": URI scheme " + quoted(scheme + ":") +
                        " is not supported (only data: URIs and file paths relative to the scene)");
        const ExternalFile file = resolveExternalFile(approved.folder, decodeUriPath(uri), approved.allowOutside);
        // A buffer file is read whole, so it has the scene file's size limit, checked before it is read.
        std::string problem = file.problem;
        std::error_code ec;
        if (problem.empty() && std::filesystem::file_size(file.path, ec) > UINT_MAX && !ec)
            problem = "which is larger than 4 GiB (not supported)";
        if (!problem.empty()) {
            // The path is the scene's folder, which the user gave, and at most an excerpt of the uri.
            const size_t pathLength = approved.folder.string().size() + kExcerptLength;
            report.fail(name + ": uri " + quoted(uri) + " names " + quoted(file.path.string(), pathLength) + ", " +
                        problem);
        }
        approved.files.insert(file.path);
    }
}

// tinygltf's own warnings, minus those about image files, which it does not read (gltf_textures.cpp
// does, and fails on a missing one that a material uses; a missing buffer is an error).
void forwardLibraryWarnings(const std::string& text, Report& report) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        const bool aboutImages = line.find("image") != std::string::npos ||
                                 line.find("Image") != std::string::npos ||
                                 line.rfind("File not found", 0) == 0;
        line = libraryText(line);
        if (!line.empty() && !aboutImages) report.warnOnce("glTF reader: " + line);
    }
}

}  // namespace

tinygltf::Model readModel(bool allowExternalFiles, Report& report, std::vector<SourceFile>& sources) {
    const std::string& path = report.path();
    const std::vector<char> bytes = readSceneFile(report);
    sources.push_back({std::filesystem::path(path).filename().string(), fnv1a({bytes.data(), bytes.size()})});
    const bool binary = (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) ||
                        std::filesystem::path(path).extension() == ".glb";
    const nlohmann::json doc = parseJson(jsonText(bytes, binary, report), report);
    checkAsset(doc, report);
    checkNesting(doc, report);
    ApprovedFiles approved;
    approved.allowOutside = allowExternalFiles;
    approved.folder = sceneFolder(report);
    approved.read = &sources;
    approveBufferFiles(doc, approved, report);

    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&keepDataUriImages, nullptr);
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
        report.fail(std::string("the glTF reader failed: ") + libraryText(e.what()));
    }
    forwardLibraryWarnings(warnings, report);
    if (!ok) report.fail("the glTF reader refused it: " + (err.empty() ? "no reason given" : libraryText(err)));
    return model;
}

std::filesystem::path sceneFolder(const Report& report) {
    std::error_code ec;
    auto folder = std::filesystem::canonical(std::filesystem::absolute(report.path()).parent_path(), ec);
    if (ec) report.fail("cannot resolve the scene's folder (" + ec.message() + ")");
    return folder;
}

}  // namespace tripath::gltf
