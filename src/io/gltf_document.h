// The glTF document as the loader checks it before tinygltf reads it: the JSON text (in a binary
// glTF, after the container's header), the parsed JSON, its nesting depth and its asset.version.
// tinygltf would say only "Invalid magic." of a renamed file, pass nlohmann's exception text on as
// it is, call a .gltf of `{}` unreadable, load a version "3.0" without a word and overflow the stack
// on arrays nested thousands deep; these checks name what is wrong in one line, quoting none of
// the file. A header of the io library's own (the loader's
// interface is gltf_loader.h).
#pragma once
#include <nlohmann/json.hpp>

#include <string_view>
#include <vector>

#include "io/gltf_checks.h"

namespace tripath::gltf {

// The JSON in the file's bytes: all of them, or for a binary glTF (GLB) its first chunk, once the
// header is checked: the magic "glTF", container version 2, the lengths within the file and a
// first chunk of type JSON.
std::string_view jsonText(const std::vector<char>& bytes, bool binary, const Report& report);

// `text` parsed; fails with "not valid JSON at line L, column C (what nlohmann found)", or for
// what nlohmann refuses in valid JSON (a number beyond double's range) with its words, shortened.
nlohmann::json parseJson(std::string_view text, const Report& report);

// The deepest nesting of arrays and objects the loader reads; the document itself is level 1.
// glTF's schema and Khronos's extensions nest about ten levels (a primitive's material variants:
// the document, "meshes", a mesh, "primitives", a primitive, "extensions",
// "KHR_materials_variants", "mappings", a mapping, "variants"); deeper JSON is application data in
// "extras" and other extensions. tinygltf converts those to its Value recursively, a stack frame
// per level: 64 levels leave six times the schema's depth and a few KiB of stack, where 16000
// overflow the main thread's 8 MiB.
constexpr size_t kMaxJsonDepth = 64;

// Fails when arrays and objects in `doc` nest deeper than kMaxJsonDepth, naming the document's
// member that does. Walks the document with a stack of its own, not by recursion.
void checkNesting(const nlohmann::json& doc, const Report& report);

// Fails unless `doc` is an object with an "asset" object whose "version" is "2.<minor>".
void checkAsset(const nlohmann::json& doc, const Report& report);

}  // namespace tripath::gltf
