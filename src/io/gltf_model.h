// Filling and writing a tinygltf::Model: the one glTF writer, shared by `tripath export`
// (gltf_writer.cpp) and the loader tests' documents (tests/test_gltf.cpp). tinygltf serialises
// the model (JSON, data: URIs, GLB chunks); this file adds the binary data the way both need it
// and the atomic write with one-line errors.
#pragma once
#include <tiny_gltf.h>

#include <cstddef>
#include <string>

namespace tripath {

// Appends `size` bytes to buffer 0 (created when missing), padded to a multiple of 4 so the next
// view stays aligned, as a new bufferView; byteStride 0 leaves the stride out. Returns its index.
int appendBufferView(tinygltf::Model& model, const void* data, size_t size, size_t byteStride = 0);

// Appends an accessor on `view`; `type` is a TINYGLTF_TYPE_* constant. Returns its index.
int appendAccessor(tinygltf::Model& model, int view, int componentType, size_t count, int type,
                   size_t byteOffset = 0);

// Sets extensions[name] to {key: value}, e.g. "KHR_materials_ior": {"ior": 1.33}.
void setExtension(tinygltf::ExtensionMap& extensions, const std::string& name, const std::string& key,
                  tinygltf::Value value);

// Writes the model to `path`, GLB when it ends in ".glb" (buffer 0 in the BIN chunk), else glTF
// JSON with every buffer embedded as a data: URI; images keep their URIs. Goes through a temporary
// file in the same folder renamed over `path`, so a failed write never leaves a truncated file.
// Throws InputError (one line naming the path) when it cannot write.
void writeGltfModel(const tinygltf::Model& model, const std::string& path);

}  // namespace tripath
