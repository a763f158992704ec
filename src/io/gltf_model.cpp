#include "io/gltf_model.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/external_files.h"

namespace tripath {

namespace fs = std::filesystem;

int appendBufferView(tinygltf::Model& model, const void* data, size_t size, size_t byteStride) {
    if (model.buffers.empty()) model.buffers.emplace_back();
    std::vector<unsigned char>& bytes = model.buffers[0].data;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bytes.size();
    view.byteLength = size;
    view.byteStride = byteStride;
    const auto* p = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), p, p + size);
    bytes.resize((bytes.size() + 3) / 4 * 4, 0);
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size()) - 1;
}

int appendAccessor(tinygltf::Model& model, int view, int componentType, size_t count, int type, size_t byteOffset) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.byteOffset = byteOffset;
    accessor.componentType = componentType;
    accessor.count = count;
    accessor.type = type;
    model.accessors.push_back(accessor);
    return static_cast<int>(model.accessors.size()) - 1;
}

void setExtension(tinygltf::ExtensionMap& extensions, const std::string& name, const std::string& key,
                  tinygltf::Value value) {
    extensions[name] = tinygltf::Value(tinygltf::Value::Object{{key, std::move(value)}});
}

std::string binBeside(const std::string& path) { return fs::path(path).replace_extension(".bin").string(); }

void checkGltfPath(const std::string& path) {
    const fs::path extension = fs::path(path).extension();
    if (extension != ".gltf" && extension != ".glb")
        throw InputError("cannot write '" + path + "': a glTF file's name ends in .gltf or .glb");
}

namespace {

// tinygltf serialises into `out`; pretty-printed JSON, so that the shipped scenes/*.gltf diff line
// by line (an embedded buffer is one line either way). No image is encoded: images keep their URIs.
void serialise(const tinygltf::Model& model, std::ostream& out, bool binary) {
    tinygltf::TinyGLTF writer;
    writer.SetImageWriter(nullptr, nullptr);
    if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/true, binary))
        out.setstate(std::ios::failbit);
}

// The JSON of a .gltf whose buffer 0 is the file `uri`. tinygltf's stream writer embeds every
// buffer, so buffer 0 goes to it empty and its entry is replaced in what comes out.
std::string jsonWithBufferFile(const tinygltf::Model& model, const std::string& uri) {
    tinygltf::Model rest = model;
    const size_t bytes = rest.buffers[0].data.size();
    rest.buffers[0].data.clear();
    std::ostringstream out;
    serialise(rest, out, false);
    nlohmann::json json = nlohmann::json::parse(out.str());
    json["buffers"][0]["byteLength"] = bytes;
    json["buffers"][0]["uri"] = uri;
    return json.dump(2);
}

}  // namespace

// WriteGltfSceneToFile would say neither why a file did not open nor that a write failed; the
// stream variant into our own file does the same serialisation and lets both be reported.
void writeGltfModel(const tinygltf::Model& model, const std::string& path, GltfBuffer buffer) {
    checkGltfPath(path);
    const bool binary = fs::path(path).extension() == ".glb";
    if (binary || buffer == GltfBuffer::Embedded || model.buffers.empty()) {
        writeFileAtomically(path, [&](std::ostream& out) { serialise(model, out, binary); });
        return;
    }
    const std::string bin = binBeside(path);
    const std::string json = jsonWithBufferFile(model, encodeUriPath(fs::path(bin).filename().string()));
    const std::vector<unsigned char>& bytes = model.buffers[0].data;
    writeFileAtomically(path, [&](std::ostream& out) {
        if (!(out << json).flush()) return;  // writeFileAtomically reports the failed stream
        writeFileAtomically(bin, [&](std::ostream& b) {
            b.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        });
    });
}

}  // namespace tripath
