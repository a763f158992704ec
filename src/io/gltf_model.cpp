#include "io/gltf_model.h"

#include <filesystem>

#include "core/atomic_file.h"

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

namespace {

// tinygltf serialises into `out`; pretty-printed JSON, so that the shipped scenes/*.gltf diff line
// by line (the base64 buffer is one line either way). No image is encoded: images keep their URIs.
void serialise(const tinygltf::Model& model, std::ostream& out, bool binary) {
    tinygltf::TinyGLTF writer;
    writer.SetImageWriter(nullptr, nullptr);
    if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/true, binary))
        out.setstate(std::ios::failbit);
}

}  // namespace

// WriteGltfSceneToFile would say neither why a file did not open nor that a write failed; the
// stream variant into our own file does the same serialisation and lets both be reported.
void writeGltfModel(const tinygltf::Model& model, const std::string& path) {
    writeFileAtomically(path, [&](std::ostream& out) { serialise(model, out, fs::path(path).extension() == ".glb"); });
}

}  // namespace tripath
