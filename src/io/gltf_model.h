// Filling and writing a tinygltf::Model: the one glTF writer, shared by `tripath export`
// (gltf_writer.cpp) and the loader tests' documents (tests/test_gltf.cpp). tinygltf serialises
// the model (JSON, data: URIs, GLB chunks); this file adds the binary data the way both need it,
// the buffer's own .bin file beside a .gltf, and the atomic write with one-line errors.
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

// Where a .gltf keeps buffer 0: in a .bin file beside it, or inside its JSON as a base64 data:
// URI (one self-contained file, its buffer a third larger). A .glb holds it in its BIN chunk.
enum class GltfBuffer { Beside, Embedded };

// The .bin beside a .gltf at `path` that GltfBuffer::Beside writes: its name with .bin.
std::string binBeside(const std::string& path);

// Throws InputError (one line naming the path) unless `path` ends in ".gltf" or ".glb".
void checkGltfPath(const std::string& path);

// Writes the model to `path`: GLB when it ends in ".glb" (buffer 0 in the BIN chunk, the JSON and
// BIN chunks padded to 4 bytes with spaces and zeros), else glTF JSON with buffer 0 as `buffer`
// says (Beside: the uri is the .bin's file name, percent-encoded) and any other buffer embedded;
// images keep their URIs. Each file goes through a temporary file in the same folder renamed over
// it, so a failed write never leaves a truncated file. The .bin is replaced once the .gltf's JSON
// is written and flushed, before the .gltf itself: a failure in between (closing or renaming the
// .gltf) is the one that leaves a new .bin beside the old .gltf.
// Throws InputError (one line naming the path) when it cannot write, or for another extension.
void writeGltfModel(const tinygltf::Model& model, const std::string& path, GltfBuffer buffer = GltfBuffer::Beside);

}  // namespace tripath
